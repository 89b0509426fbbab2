#pragma once
/// @brief When a Newton solve has converged: below the residual tolerance with a small energy
/// change, or at the round-off floor of the problem: the residual stagnates over the last
/// iterations while the energy changes and the displacement increments are at round-off, so
/// more iterations cannot improve the state (the residual is then one hair above the tolerance
/// because floating point cannot give more).

#include <string>
#include <vector>

namespace ligsim::sim {

enum class ConvergenceVerdict { iterate, converged, converged_at_floor };

/// What one accepted Newton iteration did.
struct IterationFigures {
  double relative_residual = 0.0; ///< after the iteration
  double energy_change = 0.0;     ///< |alpha d.r|, N mm
  double energy_round_off = 0.0;  ///< energy change that round-off alone produces, N mm
  /// max |d| over the free DOFs: the full Newton step, whatever the line search took of it
  /// (a stuck line search takes tiny steps of a large direction; at the floor d itself is tiny)
  double displacement_step_mm = 0.0;
};

class NewtonConvergence {
public:
  /// `length_mm` is the model size: displacement increments below 1e-8 of it are round-off
  /// for the residuals this solver reaches. `energy_tolerance`: 0 means residual_tolerance, a
  /// negative one (no_energy_test) no energy test.
  NewtonConvergence(double residual_tolerance, double energy_tolerance, double length_mm);

  /// Forgets the iterations of the previous solve.
  void restart();
  /// Records an accepted iteration.
  void record(const IterationFigures& figures);
  /// The verdict for the current state with relative residual `relative_residual`;
  /// `residual_at_force_floor`: the absolute residual is below the solver's force floor.
  ConvergenceVerdict verdict(double relative_residual, bool residual_at_force_floor) const;
  /// The floor figures of the last iterations, for reports ("residual 1.1e-08 stagnated over 3
  /// iterations, energy changes <= ..., displacement increments <= ...").
  std::string floor_summary() const;

  static constexpr double no_energy_test = -1.0;
  /// Iterations over which the residual must stagnate.
  static constexpr int window = 3;
  /// No floor lies above this relative residual: in double precision the floor of a problem
  /// is its condition number times 1e-16, and a stiffer problem than 1e10 is not solvable.
  static constexpr double max_floor = 1e-6;

private:
  double m_residual_tolerance;
  double m_energy_tolerance;
  double m_displacement_round_off_mm;
  double m_first_energy_change = 0.0;
  std::vector<IterationFigures> m_history;
};

} // namespace ligsim::sim
