#pragma once
/// @brief Stiff and extreme cases: bulk modulus 1e2-1e6 MPa, C5 up to 1e4 MPa, ten times the
/// paper's largest load, compression along the fibers, time steps 1e-5 to 1 s, an inverted
/// element, a sliver, a NaN node. Each must converge to a finite, balanced answer or stop with
/// a diagnostic naming the element or node and the cause.

#include "sim/verify/outcome.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace ligsim::sim {

struct StabilityCase {
  std::string name;
  std::string description;
};

struct StabilityResult {
  std::string name;
  std::string description;
  /// converged (static, in equilibrium with balanced reactions), completed (dynamics ran all
  /// its frames), diagnostic (stopped with a clear message) or failed (anything else).
  Outcome outcome = Outcome::failed;
  bool converged = false;
  std::string diagnostic;
  int iterations = 0; ///< Newton iterations, or frames in dynamics
  double wall_s = 0.0;
  double min_j = 0.0;
  /// |sum of reactions + applied load| / |applied load| (converged static cases)
  double balance_error = 0.0;
  double max_displacement_mm = 0.0;
};

/// How a static case ended at `x`: converged (a finite answer with balanced reactions, to 1e-6,
/// that also passes the case's own `check`), diagnostic (stopped, finite, with a message) or
/// failed (anything else).
Outcome static_outcome(const StabilityResult& result, const Eigen::VectorXd& x, bool check = true);

/// The suite, in report order.
std::vector<StabilityCase> stability_cases();

/// Runs one case by name (InputError for an unknown one). `cells` sets the cube mesh (n x n x n
/// hexes).
StabilityResult run_stability_case(const std::string& name, int cells = 8);

std::string stability_table(const std::vector<StabilityResult>& results);

} // namespace ligsim::sim
