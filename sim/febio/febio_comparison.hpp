#pragma once
/// @brief FEBio's answer to a knee flexion problem read back from its .log and measured as
/// ligsim measures its own (energy and fiber stretch of the ligament's state by the same law),
/// and the table that sets the two side by side.

#include "sim/febio/feb_problem.hpp"
#include "sim/febio/febio_log.hpp"
#include "sim/solver/hyperelastic_body.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace ligsim::sim {

/// FEBio's state at the end of one step.
struct FebioStep {
  double angle_deg = 0.0;
  Eigen::VectorXd x; ///< the ligament's node positions, flat, mm
  /// The reaction of the femur's rigid body: what the femur exerts on the ligament, N.
  Eigen::Vector3d femur_force_n = Eigen::Vector3d::Zero();
  /// Energy and mean fiber stretch of `x` under the same law as ligsim's (mJ; |F a| weighted by
  /// rest volume, in-situ pre-stretch included).
  double strain_energy_mj = 0.0;
  double mean_fiber_stretch = 0.0;
  /// FEBio's own logged strain energy density times rest volume, summed (mJ); without fiber
  /// energy when the material has an in-situ strain (FEBio reports none for it).
  double logged_energy_mj = 0.0;
  /// How far FEBio's femur is from the prescribed pose: the largest distance over the femur's
  /// attachment nodes between FEBio's rigid body (its logged position and rotation) carrying
  /// them and the pose, mm.
  double femur_pose_error_mm = 0.0;
};

/// One step per step of `problem`, from `log` (the femur is bone `femur` of the problem).
/// Throws SolverError naming the step and record when FEBio's log lacks one.
std::vector<FebioStep> febio_steps(const FebioLog& log, const FebProblem& problem,
                                   std::size_t femur, const HyperelasticBody& body);

/// One row of febio_comparison.csv.
struct ComparisonRow {
  double angle_deg = 0.0;
  double ours_femur_force_n = 0.0; ///< magnitudes
  double febio_femur_force_n = 0.0;
  double ours_energy_mj = 0.0;
  double febio_energy_mj = 0.0;
  double ours_mean_fiber_stretch = 0.0;
  double febio_mean_fiber_stretch = 0.0;
  double ours_wall_s = 0.0; ///< the whole run of each (the same on every row)
  double febio_wall_s = 0.0;
};

/// Relative difference (a - b) / |b| (0 when both are 0).
double relative_difference(double a, double b);

/// febio_comparison.csv: a header and one line per row.
std::string comparison_csv(const std::vector<ComparisonRow>& rows);

/// The same as a Markdown table, with the relative differences.
std::string comparison_table(const std::vector<ComparisonRow>& rows);

} // namespace ligsim::sim
