#include "sim/kinematics/joint_coordinates.hpp"

#include "common/error.hpp"

#include <gtest/gtest.h>

#include <random>

namespace ligsim::sim {
namespace {

/// A knee in a frame where +y is anterior and +z proximal: the subject's right is +x, so a
/// right knee's lateral side is +x and a left knee's is -x. The flexion axis A x P is +x for
/// both (lateral in the right knee, medial in the left).
JointCoordinateSystem knee(int side)
{
  JointCoordinateSystem jcs;
  jcs.origin_mm = Eigen::Vector3d(10.0, -5.0, 400.0);
  jcs.flexion_axis = Eigen::Vector3d::UnitX();
  jcs.tibial_axis = Eigen::Vector3d::UnitZ();
  jcs.side = side;
  return jcs;
}

/// Where a tibia point goes relative to the femur: the femur's motion undone.
Eigen::Vector3d tibia_point(const JointCoordinateSystem& jcs, const JointPose& pose,
                            const Eigen::Vector3d& rest)
{
  return femur_motion(jcs, pose).inverse() * rest;
}

TEST(JointCoordinates, PureFlexionTurnsTheFemurAboutTheAxis)
{
  const JointCoordinateSystem jcs = knee(+1);
  JointPose pose;
  pose.flexion_deg = 90.0;
  const Eigen::Isometry3d motion = femur_motion(jcs, pose);
  // The femoral shaft (proximal of the origin) swings posteriorly (-y).
  const Eigen::Vector3d shaft = motion * (jcs.origin_mm + Eigen::Vector3d(0, 0, 100));
  EXPECT_NEAR((shaft - (jcs.origin_mm + Eigen::Vector3d(0, -100, 0))).norm(), 0.0, 1e-9);
  // Points on the axis stay.
  const Eigen::Vector3d on_axis = jcs.origin_mm + Eigen::Vector3d(30, 0, 0);
  EXPECT_NEAR((motion * on_axis - on_axis).norm(), 0.0, 1e-9);
}

TEST(JointCoordinates, EachCoordinateKeepsItsClinicalMeaningOnBothSides)
{
  for (int side : {+1, -1}) {
    SCOPED_TRACE(side > 0 ? "right knee" : "left knee");
    const JointCoordinateSystem jcs = knee(side);
    const double medial = side > 0 ? -1.0 : 1.0; // the x direction of the knee's medial side
    const Eigen::Vector3d distal = jcs.origin_mm + Eigen::Vector3d(0, 0, -100);
    const Eigen::Vector3d anterior = jcs.origin_mm + Eigen::Vector3d(0, 30, 0);

    JointPose flexed;
    flexed.flexion_deg = 20.0;
    EXPECT_LT(tibia_point(jcs, flexed, distal).y(), -30.0); // the shank swings back

    JointPose varus;
    varus.varus_deg = 5.0;
    EXPECT_GT(medial * tibia_point(jcs, varus, distal).x() - medial * distal.x(), 8.0);

    JointPose internal;
    internal.internal_rotation_deg = 10.0;
    EXPECT_GT(medial * tibia_point(jcs, internal, anterior).x() - medial * anterior.x(), 5.0);

    JointPose shifted;
    shifted.lateral_mm = 1.0;
    shifted.anterior_mm = 2.0;
    shifted.proximal_mm = 3.0;
    const Eigen::Vector3d moved = tibia_point(jcs, shifted, jcs.origin_mm) - jcs.origin_mm;
    EXPECT_NEAR(moved.x(), -medial * 1.0, 1e-12);
    EXPECT_NEAR(moved.y(), 2.0, 1e-12);
    EXPECT_NEAR(moved.z(), 3.0, 1e-12);
  }
}

TEST(JointCoordinates, CoordinatesComeBackFromTheMotion)
{
  std::mt19937 random(7);
  std::uniform_real_distribution<double> angle(-40.0, 40.0), shift(-5.0, 5.0);
  for (int trial = 0; trial < 50; ++trial) {
    JointCoordinateSystem jcs = knee(trial % 2 == 0 ? +1 : -1);
    // Axes that are neither aligned with the frame nor exactly perpendicular.
    jcs.flexion_axis = Eigen::Vector3d(1.0, 0.1 * shift(random), 0.05 * shift(random));
    jcs.tibial_axis = Eigen::Vector3d(0.05 * shift(random), 0.08, 1.0);
    const JointPose pose{angle(random) + 60.0, angle(random) / 8.0, angle(random) / 2.0,
                         shift(random),        shift(random),       shift(random)};
    const JointPose back = joint_pose(jcs, femur_motion(jcs, pose));
    EXPECT_NEAR(back.flexion_deg, pose.flexion_deg, 1e-9);
    EXPECT_NEAR(back.varus_deg, pose.varus_deg, 1e-9);
    EXPECT_NEAR(back.internal_rotation_deg, pose.internal_rotation_deg, 1e-9);
    EXPECT_NEAR(back.lateral_mm, pose.lateral_mm, 1e-9);
    EXPECT_NEAR(back.anterior_mm, pose.anterior_mm, 1e-9);
    EXPECT_NEAR(back.proximal_mm, pose.proximal_mm, 1e-9);
  }
}

TEST(JointCoordinates, FloatingAxisIsPerpendicularToBoth)
{
  // The varus rotation turns about e3 x e1 at the current flexion: with 90 degrees of flexion,
  // varus moves the tibia's distal end (now pointing posteriorly) medially as well.
  const JointCoordinateSystem jcs = knee(+1);
  JointPose pose;
  pose.flexion_deg = 90.0;
  const Eigen::Vector3d distal = jcs.origin_mm + Eigen::Vector3d(0, 0, -100);
  const Eigen::Vector3d flexed = tibia_point(jcs, pose, distal);
  pose.varus_deg = 5.0;
  const Eigen::Vector3d tilted = tibia_point(jcs, pose, distal);
  EXPECT_LT(tilted.x() - flexed.x(), -8.0); // right knee: medial is -x
}

TEST(JointCoordinates, ParallelAxesAreAnError)
{
  JointCoordinateSystem jcs = knee(+1);
  jcs.tibial_axis = Eigen::Vector3d(1.0, 0.0, 0.1);
  EXPECT_THROW(femur_motion(jcs, JointPose{}), InputError);
  jcs.tibial_axis = Eigen::Vector3d(NAN, 0.0, 1.0);
  EXPECT_THROW(femur_motion(jcs, JointPose{}), InputError);
}

} // namespace
} // namespace ligsim::sim
