#pragma once
/// @brief Trilinear interpolation in a voxel grid.

#include "stages/geometry/grid.hpp"

#include <algorithm>
#include <cmath>

namespace ligsim {

/// Calls visit(voxel, weight) for the (up to eight) voxel centres around `p` (mm) with their
/// trilinear weights; points outside the grid are clamped to its border.
template <class T, class Visit>
void visit_trilinear_voxels(const Grid<T>& grid, const Eigen::Vector3d& p, Visit&& visit)
{
  const Eigen::Vector3d v = grid.voxel_coordinates(p);
  int base[3];
  double frac[3];
  for (int a = 0; a < 3; ++a) {
    const double c = std::clamp(v[a], 0.0, static_cast<double>(grid.dims[a] - 1));
    base[a] = std::min(static_cast<int>(std::floor(c)), std::max(grid.dims[a] - 2, 0));
    frac[a] = grid.dims[a] > 1 ? c - base[a] : 0.0;
  }
  for (int corner = 0; corner < 8; ++corner) {
    const int di = corner & 1, dj = (corner >> 1) & 1, dk = (corner >> 2) & 1;
    const double w =
        (di ? frac[0] : 1 - frac[0]) * (dj ? frac[1] : 1 - frac[1]) * (dk ? frac[2] : 1 - frac[2]);
    if (w != 0.0)
      visit(Eigen::Vector3i(std::min(base[0] + di, grid.dims[0] - 1),
                            std::min(base[1] + dj, grid.dims[1] - 1),
                            std::min(base[2] + dk, grid.dims[2] - 1)),
            w);
  }
}

/// Calls visit(value, weight) for the (up to eight) voxel centres around `p` (mm).
template <class T, class Visit>
void visit_trilinear(const Grid<T>& grid, const Eigen::Vector3d& p, Visit&& visit)
{
  visit_trilinear_voxels(grid, p,
                         [&](const Eigen::Vector3i& voxel, double w) { visit(grid(voxel), w); });
}

/// Scalar value at `p` (mm).
template <class T> double interpolate(const Grid<T>& grid, const Eigen::Vector3d& p)
{
  double result = 0.0;
  visit_trilinear(grid, p,
                  [&](const T& value, double w) { result += w * static_cast<double>(value); });
  return result;
}

} // namespace ligsim
