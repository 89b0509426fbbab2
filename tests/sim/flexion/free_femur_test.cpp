/// The femur as five unknowns: a ligament's generalized force and its condensed stiffness in the
/// free coordinates against differences of its equilibrium energy, and the free femur finding
/// the pose where a pre-stretched bar (the tests' bar knee) holds it.

#include "common/progress.hpp"
#include "sim/flexion/free_femur.hpp"
#include "tests/sim/febio/bar_knee.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <optional>

using namespace ligsim;
using namespace ligsim::sim;

namespace {

/// The bar knee's joint: its flexion axis through the bar's top, the tibial axis along the bar.
JointCoordinateSystem bar_joint()
{
  JointCoordinateSystem jcs;
  jcs.origin_mm = test::bar_axis().point_mm;
  jcs.flexion_axis = test::bar_axis().direction;
  jcs.tibial_axis = Eigen::Vector3d::UnitZ();
  jcs.side = +1;
  return jcs;
}

LigamentModel bar_ligament()
{
  LigamentModel ligament;
  ligament.name = "bar";
  ligament.model = test::bar_knee();
  return ligament;
}

std::filesystem::path cache()
{
  return std::filesystem::temp_directory_path() / "ligsim_free_femur_cache";
}

/// The ligament's generalized force and stiffness at (flexion, q) against central differences,
/// steps h, of its equilibrium energy and of the force; the stiffness within
/// `stiffness_tolerance` of its norm. Returns the stiffness.
Matrix5d expect_derivatives_of_energy(LigamentAtPose& bar, double flexion, const Vector5d& q,
                                      const Vector5d& h, double stiffness_tolerance)
{
  const FreePose pose(bar_joint(), flexion, q);
  const Vector5d g = bar.generalized_force(pose);
  const Matrix5d K = bar.stiffness(pose);
  for (int k = 0; k < 5; ++k) {
    Vector5d plus = q, minus = q;
    plus(k) += h(k);
    minus(k) -= h(k);
    EXPECT_TRUE(bar.move_to(joint_pose_of(flexion, plus))) << bar.failure();
    const double e_plus = bar.energy();
    const Vector5d g_plus = bar.generalized_force(FreePose(bar_joint(), flexion, plus));
    EXPECT_TRUE(bar.move_to(joint_pose_of(flexion, minus))) << bar.failure();
    const double e_minus = bar.energy();
    const Vector5d g_minus = bar.generalized_force(FreePose(bar_joint(), flexion, minus));
    EXPECT_NEAR(g(k), (e_plus - e_minus) / (2.0 * h(k)), 1e-4 * g.norm() + 1e-6) << k;
    const Vector5d column = (g_plus - g_minus) / (2.0 * h(k));
    EXPECT_LT((K.col(k) - column).norm(), stiffness_tolerance * K.norm()) << k << "\n"
                                                                          << K << "\n"
                                                                          << column;
  }
  return K;
}

} // namespace

TEST(FreeFemur, ALigamentsForceAndStiffnessAreTheDerivativesOfItsEnergy)
{
  Progress::set_quiet(true);
  const FlexionSettings settings = test::bar_settings(0.029);
  LigamentAtPose bar(bar_ligament(), settings, bar_joint(), cache());
  ASSERT_TRUE(bar.settle()) << bar.failure();
  Vector5d q;
  q << 0.03, -0.04, 0.2, -0.3, -0.25;
  const double flexion = 20.0;
  ASSERT_TRUE(bar.move_to(joint_pose_of(flexion, q))) << bar.failure();
  // Steps in each coordinate, rotations scaled to move points near the joint alike.
  const Vector5d h = (Vector5d() << 1e-5, 1e-5, 2e-4, 2e-4, 2e-4).finished();
  const Matrix5d K = expect_derivatives_of_energy(bar, flexion, q, h, 1e-3);
  EXPECT_LT((K - K.transpose()).norm(), 1e-9 * K.norm());
}

TEST(FreeFemur, TheContactOfTheMovingFemurEntersBothDerivativesExactly)
{
  Progress::set_quiet(true);
  // A femur block beside the bar's side, 0.1 mm off it: the barrier acts on the bar's nodes
  // there, and moves with the femur.
  FlexionSettings settings = test::bar_settings(0.029);
  settings.contact.enabled = true;
  settings.contact.barrier.d_hat_mm = 0.3;
  settings.contact.bones = {"femur"};
  LigamentModel ligament = bar_ligament();
  const TetMesh block = sim::structured_box_mesh({1, 1, 1}, {8.0, 6.0, 8.0});
  TriangleSurface side;
  side.V = block.V.rowwise() + Eigen::RowVector3d(-8.1, -1.0, 10.0);
  side.F = sim::boundary_surface(block).faces;
  ligament.model.femur = test::bone(side);
  std::filesystem::remove_all(cache() / "beside");
  LigamentAtPose bar(ligament, settings, bar_joint(), cache() / "beside");
  ASSERT_TRUE(bar.settle()) << bar.failure();
  Vector5d q;
  q << 0.01, -0.02, 0.05, -0.05, -0.05;
  const double flexion = 4.0;
  ASSERT_TRUE(bar.move_to(joint_pose_of(flexion, q))) << bar.failure();
  const Vector5d h = (Vector5d() << 1e-6, 1e-6, 2e-5, 2e-5, 2e-5).finished();
  expect_derivatives_of_energy(bar, flexion, q, h, 2e-3);
}

TEST(FreeFemur, ALigamentsPredictedEquilibriumIsRightToSecondOrderInThePosesStep)
{
  Progress::set_quiet(true);
  // The guess a trial pose's solve starts from: the footprint with the femur, the free nodes by
  // their first-order response. Halving the step must quarter its error (a footprint left where
  // it was would only halve it).
  const FlexionSettings settings = test::bar_settings(0.029);
  LigamentAtPose bar(bar_ligament(), settings, bar_joint(), cache());
  ASSERT_TRUE(bar.settle()) << bar.failure();
  const double flexion = 20.0;
  Vector5d q;
  q << 0.03, -0.04, 0.2, -0.3, -0.25;
  ASSERT_TRUE(bar.move_to(joint_pose_of(flexion, q))) << bar.failure();
  const LigamentAtPose::Equilibrium at_q = bar.equilibrium();
  Vector5d step;
  step << 0.02, 0.01, 0.1, 0.1, -0.1;
  double errors[2];
  for (int halving = 0; halving < 2; ++halving) {
    bar.restore(at_q);
    bar.stiffness(FreePose(bar_joint(), flexion, q));
    const JointPose target = joint_pose_of(flexion, q + std::ldexp(1.0, -halving) * step);
    const std::optional<Eigen::VectorXd> guess = bar.predicted_positions(target);
    ASSERT_TRUE(guess.has_value());
    ASSERT_TRUE(bar.move_to(target)) << bar.failure();
    errors[halving] = (*guess - bar.positions()).lpNorm<Eigen::Infinity>();
  }
  EXPECT_GT(errors[1], 0.0);
  EXPECT_LT(errors[1], 0.3 * errors[0]) << errors[0] << " " << errors[1];
  // No guess across a change of flexion.
  bar.restore(at_q);
  bar.stiffness(FreePose(bar_joint(), flexion, q));
  EXPECT_FALSE(bar.predicted_positions(joint_pose_of(flexion + 1.0, q)).has_value());
}

TEST(FreeFemur, APrestretchedBarPullsTheFreeFemurToWhereItsForceVanishes)
{
  Progress::set_quiet(true);
  // No loads: the femur held only by the bar, pre-stretched 2.9 % along its fibers, comes down
  // until the bar pulls no more.
  const FlexionSettings settings = test::bar_settings(0.029);
  std::vector<LigamentAtPose> ligaments;
  ligaments.emplace_back(bar_ligament(), settings, bar_joint(), cache());
  FreeKneeSettings free;
  free.loads.compression_n = 0.0;
  const FreeFemurResult found = find_free_path(ligaments, nullptr, bar_joint(), {0.0}, free);
  ASSERT_TRUE(found.success) << found.failure;
  const FreeAngle& at = found.angles.front();
  EXPECT_TRUE(at.converged);
  EXPECT_LE(at.iterations, 10);
  // The femur's force: none left of the pre-stretch's pull (at the built pose: N).
  EXPECT_LT(at.ligament_femur_forces_n.front().norm(), 1e-3);
  // The bar shortened along the tibial axis, by less than its fibers' pre-stretch (20 mm x 2.9 %
  // / 1.029 = 0.56 mm): its ground substance, squeezed as it shortens, holds the rest. Measured:
  // 0.34 mm.
  EXPECT_GT(at.pose.proximal_mm, 0.2);
  EXPECT_LT(at.pose.proximal_mm, 20.0 * 0.029 / 1.029);
  EXPECT_NEAR(at.pose.anterior_mm, 0.0, 1e-6);

  // A 10 N anterior load on the tibia: the bar shears until it holds it.
  free.loads.anterior_n = 10.0;
  std::vector<LigamentAtPose> again;
  again.emplace_back(bar_ligament(), settings, bar_joint(), cache());
  const FreeFemurResult drawn = find_free_path(again, nullptr, bar_joint(), {0.0}, free);
  ASSERT_TRUE(drawn.success) << drawn.failure;
  EXPECT_GT(drawn.angles.front().pose.anterior_mm, 0.0);
  // The bar's pull on the femur is the load: 10 N.
  EXPECT_NEAR(drawn.angles.front().ligament_femur_forces_n.front().norm(), 10.0, 0.05);
}
