#include "sim/kinematics/joint_coordinates.hpp"

#include "common/error.hpp"

#include <cmath>

namespace ligsim::sim {

namespace {

constexpr double degree = M_PI / 180.0;

/// The tibia's rotation and translation relative to the femur, in the femur's (rest) frame.
struct TibiaMotion {
  Eigen::Matrix3d rotation;
  Eigen::Vector3d translation_mm; ///< of the tibia, in the femur's frame
};

TibiaMotion tibia_motion(const JointCoordinateSystem& jcs, const JointPose& pose)
{
  const Eigen::Matrix3d axes = joint_axes(jcs);
  const double side = jcs.side >= 0 ? 1.0 : -1.0;
  TibiaMotion motion;
  motion.rotation = (Eigen::AngleAxisd(-pose.flexion_deg * degree, axes.col(0)) *
                     Eigen::AngleAxisd(side * pose.varus_deg * degree, axes.col(1)) *
                     Eigen::AngleAxisd(side * pose.internal_rotation_deg * degree, axes.col(2)))
                        .toRotationMatrix();
  // The knee's lateral direction is e1 in a right knee and -e1 in a left one.
  const Eigen::Vector3d in_tibia = side * pose.lateral_mm * axes.col(0) +
                                   pose.anterior_mm * axes.col(1) + pose.proximal_mm * axes.col(2);
  motion.translation_mm = motion.rotation * in_tibia;
  return motion;
}

} // namespace

Eigen::Matrix3d joint_axes(const JointCoordinateSystem& jcs)
{
  const Eigen::Vector3d& e1 = jcs.flexion_axis;
  const Eigen::Vector3d& e3 = jcs.tibial_axis;
  if (!e1.allFinite() || !e3.allFinite() || !jcs.origin_mm.allFinite() || e1.norm() < 1e-12 ||
      e3.norm() < 1e-12)
    fail("joint coordinate system: the flexion axis, the tibial axis and the origin must be "
         "finite and non-zero");
  const Eigen::Vector3d u1 = e1.normalized();
  const Eigen::Vector3d across = e3.normalized() - e3.normalized().dot(u1) * u1;
  // Closer than 30 degrees to parallel: no knee has its tibia lying along the flexion axis.
  if (across.norm() < 0.5)
    fail("joint coordinate system: the tibial axis is {:.1f} degrees from the flexion axis; "
         "they must be roughly perpendicular (check the proximal direction and the axis)",
         std::acos(std::min(1.0, std::abs(e3.normalized().dot(u1)))) / degree);
  Eigen::Matrix3d axes;
  axes.col(0) = u1;
  axes.col(2) = across.normalized();
  axes.col(1) = axes.col(2).cross(axes.col(0));
  return axes;
}

Eigen::Isometry3d femur_motion(const JointCoordinateSystem& jcs, const JointPose& pose)
{
  // The tibia relative to the femur: y -> O + R (y - O) + t. With the tibia held, the femur
  // moves by the inverse: x -> O + R^T (x - O - t).
  const TibiaMotion tibia = tibia_motion(jcs, pose);
  Eigen::Isometry3d femur = Eigen::Isometry3d::Identity();
  femur.linear() = tibia.rotation.transpose();
  femur.translation() =
      jcs.origin_mm - tibia.rotation.transpose() * (jcs.origin_mm + tibia.translation_mm);
  return femur;
}

JointPose joint_pose(const JointCoordinateSystem& jcs, const Eigen::Isometry3d& femur_motion)
{
  const Eigen::Matrix3d axes = joint_axes(jcs);
  const double side = jcs.side >= 0 ? 1.0 : -1.0;
  // The tibia's rotation relative to the femur, in the JCS's rest axes: a Cardan X-Y-Z matrix.
  const Eigen::Matrix3d tibia = femur_motion.linear().transpose();
  const Eigen::Matrix3d r = axes.transpose() * tibia * axes;
  const double beta = std::asin(std::clamp(r(0, 2), -1.0, 1.0));
  const double alpha = std::atan2(-r(1, 2), r(2, 2));
  const double gamma = std::atan2(-r(0, 1), r(0, 0));
  JointPose pose;
  pose.flexion_deg = -alpha / degree;
  pose.varus_deg = side * beta / degree;
  pose.internal_rotation_deg = side * gamma / degree;
  // x -> O + R^T (x - O - t): the translation part is O - R^T (O + t).
  const Eigen::Vector3d t = tibia * (jcs.origin_mm - femur_motion.translation()) - jcs.origin_mm;
  const Eigen::Vector3d in_tibia = axes.transpose() * (tibia.transpose() * t);
  pose.lateral_mm = side * in_tibia.x();
  pose.anterior_mm = in_tibia.y();
  pose.proximal_mm = in_tibia.z();
  return pose;
}

} // namespace ligsim::sim
