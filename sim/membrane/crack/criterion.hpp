#pragma once
/// @brief The fiber-aware tearing criterion of Allard et al., eqs. 4 to 6.
///
/// Every vector here is a unit vector of the membrane's rest (material) frame; stresses are the
/// co-rotational element stresses in that frame, (sigma_x, sigma_y, tau_xy) in MPa.

#include <Eigen/Core>

#include <cmath>

namespace ligsim::membrane {

struct TearThresholds {
  double fiber_mpa = 0.0;           ///< bar sigma_F: stress along the fibers that breaks them
  double transverse_mpa = 0.0;      ///< bar sigma_T: stress across the fibers that separates them
  double steepness = 1.0;           ///< alpha in eq. 6
  double max_turn_rad = M_PI / 2.0; ///< theta_P in eq. 4: largest turn from the previous direction
};

/// Eq. 5: the normal stress along the unit direction u (the angle theta_u of u from x enters
/// as cos and sin).
double normal_stress_along(const Eigen::Vector3d& stress, const Eigen::Vector2d& u);

/// Eq. 6: the threshold along the unit direction u, between bar sigma_T (u across the fiber f)
/// and bar sigma_F (u along f), with steepness alpha.
double threshold_along(const TearThresholds& thresholds, const Eigen::Vector2d& u,
                       const Eigen::Vector2d& fiber);

/// Eq. 4 without the gate: the stress across the crack line d (along d_perp = d x n) over the
/// threshold along d_perp. A tear along d opens when this exceeds 1.
double criterion_value(const TearThresholds& thresholds, const Eigen::Vector3d& stress,
                       const Eigen::Vector2d& fiber, const Eigen::Vector2d& d);

/// The gate of eq. 4: H(d . p - cos theta_P).
bool within_turn(const TearThresholds& thresholds, const Eigen::Vector2d& d,
                 const Eigen::Vector2d& previous);

} // namespace ligsim::membrane
