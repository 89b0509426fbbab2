#pragma once
/// @brief Selecting nodes by geometry: on a plane, inside a box.

#include "common/mesh.hpp"

#include <Eigen/Core>

#include <vector>

namespace ligsim::sim {

/// Nodes with |V(n, axis) - value_mm| <= tolerance_mm, ascending.
std::vector<int> nodes_on_plane(const Points& V, int axis, double value_mm, double tolerance_mm);

/// Nodes inside the closed box [min_mm, max_mm], ascending.
std::vector<int> nodes_in_box(const Points& V, const Eigen::Vector3d& min_mm,
                              const Eigen::Vector3d& max_mm);

} // namespace ligsim::sim
