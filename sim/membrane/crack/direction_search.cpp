#include "sim/membrane/crack/direction_search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace ligsim::membrane {
namespace {

Eigen::Vector2d unit_at(double angle)
{
  return {std::cos(angle), std::sin(angle)};
}

double angle_of(const Eigen::Vector2d& v)
{
  return std::atan2(v.y(), v.x());
}

/// The search interval [lo, hi] of angles and the criterion on it.
struct SearchInterval {
  double lo = 0.0;
  double hi = M_PI;

  /// An angle equivalent to `angle` for the criterion (c(d) = c(-d)) inside the interval, if any.
  std::optional<double> place(double angle) const
  {
    const double k = std::ceil((lo - angle) / M_PI - 1e-12);
    const double placed = angle + k * M_PI;
    if (placed <= hi + 1e-12)
      return std::min(placed, hi);
    return std::nullopt;
  }
};

/// Where c can peak off a smooth maximum: the kinks of the threshold (d along and across the
/// fiber), the peak of the numerator (d across the largest principal stress) and, with a
/// previous direction, the edges of the theta_P cone.
std::vector<double> exact_candidates(const SearchInterval& interval, const Eigen::Vector3d& stress,
                                     const Eigen::Vector2d& fiber, bool gated)
{
  const double fiber_angle = angle_of(fiber);
  const double principal_angle = angle_of(largest_principal_stress(stress).second);
  std::vector<double> exact;
  for (double special : {fiber_angle, fiber_angle + M_PI / 2, principal_angle + M_PI / 2})
    if (const auto placed = interval.place(special))
      exact.push_back(*placed);
  if (gated) {
    exact.push_back(interval.lo);
    exact.push_back(interval.hi);
  }
  return exact;
}

} // namespace

double screen_tear_value(const TearThresholds& thresholds, const Eigen::Vector3d& stress,
                         const Eigen::Vector2d& fiber)
{
  const SearchInterval interval;
  double best = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < 18; ++i)
    best = std::max(best, criterion_value(thresholds, stress, fiber, unit_at(i * M_PI / 18.0)));
  for (double angle : exact_candidates(interval, stress, fiber, false))
    best = std::max(best, criterion_value(thresholds, stress, fiber, unit_at(angle)));
  return best;
}

std::pair<double, Eigen::Vector2d> largest_principal_stress(const Eigen::Vector3d& stress)
{
  const double mean = 0.5 * (stress[0] + stress[1]);
  const double radius = std::hypot(0.5 * (stress[0] - stress[1]), stress[2]);
  const double angle = 0.5 * std::atan2(2.0 * stress[2], stress[0] - stress[1]);
  return {mean + radius, unit_at(angle)};
}

TearDirection best_tear_direction(const TearThresholds& thresholds, const Eigen::Vector3d& stress,
                                  const Eigen::Vector2d& fiber,
                                  const std::optional<Eigen::Vector2d>& previous,
                                  double grid_step_rad)
{
  SearchInterval interval;
  if (previous) {
    const double turn = std::min(thresholds.max_turn_rad, M_PI);
    const double centre = angle_of(*previous);
    interval = {centre - turn, centre + turn};
  }
  const auto value_at = [&](double angle) {
    return criterion_value(thresholds, stress, fiber, unit_at(angle));
  };

  // Exhaustive search on a grid that includes both ends of the interval.
  const double span = interval.hi - interval.lo;
  const int intervals = std::max(1, static_cast<int>(std::ceil(span / grid_step_rad - 1e-9)));
  const double step = span / intervals;
  double best_angle = interval.lo;
  double best_value = value_at(best_angle);
  int best_index = 0;
  for (int i = 1; i <= intervals; ++i) {
    const double angle = interval.lo + i * step;
    const double value = value_at(angle);
    if (value > best_value) {
      best_value = value;
      best_angle = angle;
      best_index = i;
    }
  }

  // Golden-section refinement between the grid neighbours of the best point.
  double a = interval.lo + std::max(0, best_index - 1) * step;
  double b = interval.lo + std::min(intervals, best_index + 1) * step;
  const double ratio = (std::sqrt(5.0) - 1.0) / 2.0;
  double x1 = b - ratio * (b - a), x2 = a + ratio * (b - a);
  double f1 = value_at(x1), f2 = value_at(x2);
  while (b - a > 1e-10) {
    if (f1 < f2) {
      a = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + ratio * (b - a);
      f2 = value_at(x2);
    } else {
      b = x2;
      x2 = x1;
      f2 = f1;
      x1 = b - ratio * (b - a);
      f1 = value_at(x1);
    }
  }
  const double refined = 0.5 * (a + b);
  if (value_at(refined) > best_value) {
    best_value = value_at(refined);
    best_angle = refined;
  }

  // The exact candidates win ties with the numerical optimum, which is only accurate to
  // rounding.
  const std::vector<double> exact = exact_candidates(interval, stress, fiber, previous.has_value());
  double exact_value = -std::numeric_limits<double>::infinity(), exact_angle = 0.0;
  for (double angle : exact) {
    const double value = value_at(angle);
    if (value > exact_value) {
      exact_value = value;
      exact_angle = angle;
    }
  }
  if (exact_value >= best_value - 1e-12 * (1.0 + std::abs(best_value))) {
    best_value = exact_value;
    best_angle = exact_angle;
  }
  return {unit_at(best_angle), best_value};
}

} // namespace ligsim::membrane
