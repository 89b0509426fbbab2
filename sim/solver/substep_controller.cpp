#include "sim/solver/substep_controller.hpp"

#include <algorithm>

namespace ligsim::sim {

double SubstepController::next_target(double t, double t_end) const
{
  const double remaining = t_end - t;
  // A sliver of a step left over costs a whole Newton solve for nothing: merge it.
  if (m_size >= remaining || remaining - m_size < 0.1 * m_size)
    return t_end;
  return t + m_size;
}

void SubstepController::accepted(int iterations)
{
  if (iterations <= easy_iterations)
    m_size = std::min(1.0, 2.0 * m_size);
  else if (iterations > hard_iterations)
    m_size *= 0.5;
}

} // namespace ligsim::sim
