#pragma once
/// @brief The tear direction: the maximiser of the criterion of eq. 4 over all directions.

#include "sim/membrane/crack/criterion.hpp"

#include <Eigen/Core>

#include <cmath>
#include <optional>
#include <utility>

namespace ligsim::membrane {

struct TearDirection {
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX(); ///< unit, rest frame
  double value = 0.0;                                   ///< c(direction), eq. 4
};

/// Maximises c(d) over directions d. Without `previous` (initiation) the crack line is
/// undirected and every line is a candidate; with it, only the d within theta_P of `previous`.
///
/// An exhaustive search on a grid no coarser than `grid_step_rad`, then the exact optimum:
/// a golden-section refinement around the best grid point, and the points where c has a kink
/// or its numerator peaks (d along and across the fiber, d across the largest principal stress,
/// the edges of the theta_P cone). For sigma_F = sigma_T and theta_P >= 90 degrees this is the
/// maximum principal stress criterion: d is perpendicular to the largest principal stress.
TearDirection best_tear_direction(const TearThresholds& thresholds, const Eigen::Vector3d& stress,
                                  const Eigen::Vector2d& fiber,
                                  const std::optional<Eigen::Vector2d>& previous,
                                  double grid_step_rad = M_PI / 180.0);

/// A cheap estimate of max_d c(d) without a gate: c on a 10-degree grid and at the exact
/// candidates above. It misses the maximum only where c peaks smoothly between grid points,
/// by a few percent at most; tearing uses it to pick the elements worth a full search.
double screen_tear_value(const TearThresholds& thresholds, const Eigen::Vector3d& stress,
                         const Eigen::Vector2d& fiber);

/// Largest principal stress and the unit direction it acts along, MPa.
std::pair<double, Eigen::Vector2d> largest_principal_stress(const Eigen::Vector3d& stress);

} // namespace ligsim::membrane
