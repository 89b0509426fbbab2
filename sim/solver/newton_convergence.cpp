#include "sim/solver/newton_convergence.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace ligsim::sim {

namespace {

/// Relative displacement increment that counts as round-off: a residual at the floor (about
/// 1e-8 of the load) moves the nodes by about that fraction of the model size.
constexpr double displacement_round_off = 1e-8;
/// Stagnation: the residual fell by less than this factor over the window.
constexpr double stagnation_ratio = 0.5;

} // namespace

NewtonConvergence::NewtonConvergence(double residual_tolerance, double energy_tolerance,
                                     double length_mm)
    : m_residual_tolerance(residual_tolerance)
    , m_energy_tolerance(energy_tolerance > 0.0    ? energy_tolerance
                         : energy_tolerance == 0.0 ? residual_tolerance
                                                   : std::numeric_limits<double>::infinity())
    , m_displacement_round_off_mm(displacement_round_off * length_mm)
{
}

void NewtonConvergence::restart()
{
  m_history.clear();
  m_first_energy_change = 0.0;
}

void NewtonConvergence::record(const IterationFigures& figures)
{
  if (m_history.empty())
    m_first_energy_change = figures.energy_change;
  m_history.push_back(figures);
}

ConvergenceVerdict NewtonConvergence::verdict(double relative_residual,
                                              bool residual_at_force_floor) const
{
  const bool small_residual = relative_residual <= m_residual_tolerance || residual_at_force_floor;
  const bool small_energy_change =
      m_history.empty() || std::isinf(m_energy_tolerance) ||
      m_history.back().energy_change <= m_energy_tolerance * m_first_energy_change;
  if (small_residual && small_energy_change)
    return ConvergenceVerdict::converged;
  if (static_cast<int>(m_history.size()) <= window || relative_residual > max_floor)
    return ConvergenceVerdict::iterate;
  // Stagnation: no real progress over the window, and every step in it at round-off.
  const std::size_t first = m_history.size() - window;
  const double before = m_history[first - 1].relative_residual;
  double best = relative_residual;
  for (std::size_t i = first; i < m_history.size(); ++i) {
    const IterationFigures& f = m_history[i];
    if (f.energy_change > f.energy_round_off ||
        f.displacement_step_mm > m_displacement_round_off_mm)
      return ConvergenceVerdict::iterate;
    best = std::min(best, f.relative_residual);
  }
  return best > stagnation_ratio * before ? ConvergenceVerdict::converged_at_floor
                                          : ConvergenceVerdict::iterate;
}

std::string NewtonConvergence::floor_summary() const
{
  double energy = 0.0;
  double round_off = 0.0;
  double step = 0.0;
  const std::size_t count = std::min<std::size_t>(m_history.size(), window);
  for (std::size_t i = m_history.size() - count; i < m_history.size(); ++i) {
    energy = std::max(energy, m_history[i].energy_change);
    round_off = std::max(round_off, m_history[i].energy_round_off);
    step = std::max(step, m_history[i].displacement_step_mm);
  }
  return fmt::format("relative residual {:.3g} (tolerance {:.3g}) stagnated over {} iterations "
                     "with energy changes <= {:.2g} N mm (round-off {:.2g}) and displacement "
                     "increments <= {:.2g} mm",
                     m_history.empty() ? 0.0 : m_history.back().relative_residual,
                     m_residual_tolerance, count, energy, round_off, step);
}

} // namespace ligsim::sim
