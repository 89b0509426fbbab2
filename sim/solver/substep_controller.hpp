#pragma once
/// @brief Automatic sub-stepping of the load factor, as FEBio's auto time stepper: the user's
/// load steps are output steps; inside each, the sub-step grows after easy steps, stays after
/// moderate ones, shrinks after hard ones and is halved after a failed one.

namespace ligsim::sim {

class SubstepController {
public:
  /// Newton iterations of an easy sub-step (grow by 2) and of a hard one (shrink by 2).
  static constexpr int easy_iterations = 6;
  static constexpr int hard_iterations = 15;

  /// Starts with sub-steps of `initial` (load factor).
  explicit SubstepController(double initial = 1.0)
      : m_size(initial)
  {
  }

  /// The next sub-step's end from the current load factor `t` within the output step ending at
  /// `t_end` (never overshoots it; a remainder below a tenth of a step is merged in).
  double next_target(double t, double t_end) const;
  /// A sub-step converged in `iterations` Newton iterations.
  void accepted(int iterations);
  /// A sub-step of length `attempted` failed: half of it next.
  void rejected(double attempted) { m_size = 0.5 * attempted; }
  double size() const { return m_size; }

private:
  double m_size;
};

} // namespace ligsim::sim
