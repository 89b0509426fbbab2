/// The knee sweep on a small ligament-like bar: rigid-body invariance, exact femur motion,
/// reproducibility, the pre-stretched rest state, the interactive mode and bad inputs.

#include "common/error.hpp"
#include "common/progress.hpp"
#include "sim/flexion/knee_flexion.hpp"
#include "sim/mesh/structured_mesh.hpp"

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>

using namespace ligsim::sim;

namespace {

constexpr double length_mm = 20.0;

/// A 4 x 4 x 20 mm bar along z with fibers along it: tibia attached at z = 0, femur at z = 20.
KneeModel bar_knee()
{
  KneeModel model;
  model.mesh = structured_box_mesh({2, 2, 8}, {4.0, 4.0, length_mm});
  model.fiber_directions = Eigen::MatrixX3d::Zero(model.mesh.T.rows(), 3);
  model.fiber_directions.col(2).setOnes();
  for (Eigen::Index n = 0; n < model.mesh.V.rows(); ++n) {
    if (model.mesh.V(n, 2) < 1e-9)
      model.tibia_nodes.push_back(static_cast<int>(n));
    if (model.mesh.V(n, 2) > length_mm - 1e-9)
      model.femur_nodes.push_back(static_cast<int>(n));
  }
  return model;
}

/// Flexion about the x axis through the middle of the femoral attachment.
FlexionAxis bar_axis()
{
  return {Eigen::Vector3d(2.0, 2.0, length_mm), Eigen::Vector3d::UnitX()};
}

FlexionSettings sweep_settings(double in_situ_strain)
{
  FlexionSettings settings;
  settings.in_situ_strain = in_situ_strain;
  settings.axis.source = AxisSettings::Source::points;
  settings.axis.first_mm = bar_axis().point_mm;
  settings.axis.second_mm = bar_axis().point_mm + bar_axis().direction;
  settings.images = false;
  return settings;
}

struct Sweep {
  SweepResult result;
  std::vector<Eigen::VectorXd> states;
};

Sweep sweep(const KneeModel& model, const BoundaryConditions& conditions,
            const FlexionSettings& settings)
{
  ligsim::Progress::set_quiet(true);
  const HyperelasticBody body = ligament_body(model, settings.material, settings.in_situ_strain);
  Sweep run;
  run.result = run_flexion_sweep(body, conditions, settings,
                                 [&](const AngleResult&, const HyperelasticBody&,
                                     const Eigen::VectorXd& x) { run.states.push_back(x); });
  return run;
}

} // namespace

TEST(KneeFlexion, TurningBonesAndLigamentTogetherCostsNoEnergy)
{
  const KneeModel model = bar_knee();
  const FlexionSettings settings = sweep_settings(0.0);
  BoundaryConditions conditions = knee_conditions(model, bar_axis(), 90.0);
  conditions.constraints[0].rigid = conditions.constraints[1].rigid; // the tibia turns too
  const Sweep run = sweep(model, conditions, settings);
  ASSERT_TRUE(run.result.success) << run.result.failure;
  ASSERT_EQ(run.result.angles.size(), settings.angles_deg.size());
  const double energy_unit = settings.material.mu_mpa * 4.0 * 4.0 * length_mm; // mu V, mJ
  double worst = 0.0;
  for (const AngleResult& angle : run.result.angles) {
    EXPECT_TRUE(angle.converged);
    worst = std::max(worst, std::abs(angle.strain_energy_mj));
    EXPECT_NEAR(angle.max_fiber_stretch, 1.0, 1e-9);
  }
  RecordProperty("worst_energy_over_mu_v", fmt::format("{:.3e}", worst / energy_unit));
  EXPECT_LT(worst, 1e-12 * energy_unit);
}

TEST(KneeFlexion, FemurAttachmentFollowsTheRotationExactly)
{
  const KneeModel model = bar_knee();
  const FlexionSettings settings = sweep_settings(0.029);
  const Sweep run = sweep(model, knee_conditions(model, bar_axis(), 90.0), settings);
  ASSERT_TRUE(run.result.success) << run.result.failure;
  for (std::size_t a = 0; a < run.states.size(); ++a) {
    const double angle = settings.angles_deg[a] * M_PI / 180.0;
    const Eigen::Matrix3d R = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitX()).toRotationMatrix();
    for (int n : model.femur_nodes) {
      const Eigen::Vector3d rest = model.mesh.V.row(n).transpose();
      const Eigen::Vector3d expected = bar_axis().point_mm + R * (rest - bar_axis().point_mm);
      EXPECT_LT((run.states[a].segment<3>(3 * n) - expected).norm(), 1e-12)
          << "node " << n << " at " << settings.angles_deg[a] << " deg";
    }
    for (int n : model.tibia_nodes)
      EXPECT_EQ(run.states[a].segment<3>(3 * n), model.mesh.V.row(n).transpose());
  }
  // Bending the ligament costs energy that grows with the angle.
  EXPECT_GT(run.result.angles.back().strain_energy_mj, run.result.angles[1].strain_energy_mj);
}

TEST(KneeFlexion, SweepIsReproducible)
{
  const KneeModel model = bar_knee();
  const FlexionSettings settings = sweep_settings(0.029);
  const BoundaryConditions conditions = knee_conditions(model, bar_axis(), 90.0);
  const Sweep first = sweep(model, conditions, settings);
  const Sweep second = sweep(model, conditions, settings);
  ASSERT_TRUE(first.result.success && second.result.success);
  ASSERT_EQ(first.states.size(), second.states.size());
  for (std::size_t a = 0; a < first.states.size(); ++a) {
    EXPECT_EQ(first.states[a], second.states[a]) << settings.angles_deg[a] << " deg";
    EXPECT_EQ(first.result.angles[a].strain_energy_mj, second.result.angles[a].strain_energy_mj);
    EXPECT_EQ(first.result.angles[a].newton_iterations, second.result.angles[a].newton_iterations);
  }
}

TEST(KneeFlexion, PrestretchedRestStateIsInEquilibriumWithFibersInTension)
{
  const KneeModel model = bar_knee();
  FlexionSettings settings = sweep_settings(0.029);
  settings.angles_deg = {0.0};
  const Sweep run = sweep(model, knee_conditions(model, bar_axis(), 0.0), settings);
  ASSERT_TRUE(run.result.success) << run.result.failure;
  const AngleResult& rest = run.result.angles.front();
  // The attachments pull the ligament's ends apart with equal and opposite forces.
  const double force = rest.femur_force_n.norm();
  EXPECT_GT(rest.femur_force_n.z(), 0.0);
  EXPECT_LT(rest.tibia_force_n.z(), 0.0);
  RecordProperty("femur_force_n", fmt::format("{:.6g}", force));
  RecordProperty("force_imbalance_n",
                 fmt::format("{:.3e}", (rest.femur_force_n + rest.tibia_force_n).norm()));
  EXPECT_LT((rest.femur_force_n + rest.tibia_force_n).norm(),
            settings.newton.residual_tolerance * 10.0 * force);
  // Fibers stretched beyond their stress-free length: in tension. (The clamped ends keep the
  // bar's length, so only the cross-section relaxes.)
  EXPECT_GT(rest.mean_fiber_stretch, 1.02);
  EXPECT_GT(rest.strain_energy_mj, 0.0);
  EXPECT_LT(rest.strain_energy_mj, run.result.unrelaxed_energy_mj);
}

TEST(KneeFlexion, InteractiveSweepReachesEveryAngleNearEquilibrium)
{
  const KneeModel model = bar_knee();
  FlexionSettings settings = sweep_settings(0.029);
  settings.angles_deg = {0.0, 30.0, 60.0};
  const BoundaryConditions conditions = knee_conditions(model, bar_axis(), 60.0);
  const Sweep quasi_static = sweep(model, conditions, settings);
  settings.mode = FlexionMode::interactive;
  settings.interactive.angular_speed_deg_s = 30.0;
  settings.interactive.time_step_s = 0.05;
  const Sweep interactive = sweep(model, conditions, settings);
  ASSERT_TRUE(interactive.result.success) << interactive.result.failure;
  ASSERT_EQ(interactive.result.angles.size(), 3u);
  EXPECT_EQ(interactive.result.frames, 40);
  EXPECT_EQ(interactive.result.angles[1].frame, 20);
  EXPECT_GT(interactive.result.frames_per_second, 0.0);
  // Slow, damped motion stays close to the quasi-static path.
  for (std::size_t a = 0; a < 3; ++a) {
    const double expected = quasi_static.result.angles[a].strain_energy_mj;
    EXPECT_NEAR(interactive.result.angles[a].strain_energy_mj, expected, 0.05 * expected)
        << settings.angles_deg[a] << " deg";
  }
}

TEST(KneeFlexion, BadSettingsAreRejected)
{
  FlexionSettings settings = sweep_settings(0.029);
  settings.angles_deg = {};
  EXPECT_THROW(validate(settings), ligsim::InputError);
  settings.angles_deg = {0.0, 45.0, 30.0};
  EXPECT_THROW(validate(settings), ligsim::InputError);
  settings.angles_deg = {0.0, 90.0};
  settings.axis.second_mm = settings.axis.first_mm;
  EXPECT_THROW(validate(settings), ligsim::InputError);
  const KneeModel model = bar_knee();
  EXPECT_THROW(resolve_flexion_axis(model, settings.axis), ligsim::InputError);
  AxisSettings fitted;
  fitted.source = AxisSettings::Source::condyles; // no posterior direction given
  EXPECT_THROW(resolve_flexion_axis(model, fitted), ligsim::InputError);
}
