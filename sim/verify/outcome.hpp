#pragma once
/// @brief How a verification case ended: one word per outcome, the same in every report.

#include <ostream>
#include <string>

namespace ligsim::sim {

enum class Outcome {
  converged,  ///< static: in equilibrium (every angle of a sweep)
  completed,  ///< dynamics or an interactive sweep: every frame reached
  diagnostic, ///< stopped with a clear message naming where
  skipped,    ///< not run (its input was not given)
  failed,     ///< anything else: a wrong, non-finite or unexplained result
};

/// The word the reports print: "converged", "completed", "diagnostic", "skipped" or "FAILED".
inline std::string to_string(Outcome outcome)
{
  switch (outcome) {
  case Outcome::converged:
    return "converged";
  case Outcome::completed:
    return "completed";
  case Outcome::diagnostic:
    return "diagnostic";
  case Outcome::skipped:
    return "skipped";
  case Outcome::failed:
    break;
  }
  return "FAILED";
}

inline std::ostream& operator<<(std::ostream& out, Outcome outcome)
{
  return out << to_string(outcome);
}

} // namespace ligsim::sim
