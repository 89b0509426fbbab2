#include "sim/membrane/crack/criterion.hpp"

#include <algorithm>
#include <cmath>

namespace ligsim::membrane {

double normal_stress_along(const Eigen::Vector3d& stress, const Eigen::Vector2d& u)
{
  const double c = u.x(), s = u.y();
  return c * c * stress[0] + s * s * stress[1] + 2.0 * s * c * stress[2];
}

double threshold_along(const TearThresholds& thresholds, const Eigen::Vector2d& u,
                       const Eigen::Vector2d& fiber)
{
  const double alignment = std::min(1.0, std::abs(u.dot(fiber)));
  const double closeness = 1.0 - 2.0 / M_PI * std::acos(alignment); // 1 along f, 0 across
  return thresholds.transverse_mpa + (thresholds.fiber_mpa - thresholds.transverse_mpa) *
                                         std::pow(closeness, thresholds.steepness);
}

double criterion_value(const TearThresholds& thresholds, const Eigen::Vector3d& stress,
                       const Eigen::Vector2d& fiber, const Eigen::Vector2d& d)
{
  const Eigen::Vector2d across(d.y(), -d.x()); // d x n with n = +z
  return normal_stress_along(stress, across) / threshold_along(thresholds, across, fiber);
}

bool within_turn(const TearThresholds& thresholds, const Eigen::Vector2d& d,
                 const Eigen::Vector2d& previous)
{
  // A hair of slack so that a direction exactly on the cone's edge stays inside.
  return d.dot(previous) >= std::cos(thresholds.max_turn_rad) - 1e-12;
}

} // namespace ligsim::membrane
