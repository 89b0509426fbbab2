#pragma once
/// @brief Unsigned distance from points to a triangle surface (CGAL AABB tree, kept out of
/// headers).

#include "common/mesh.hpp"

#include <Eigen/Core>

namespace ligsim::tetmesh {

/// Distance (mm) from each row of `points` (#P x 3, mm) to the nearest triangle of `surface`.
Eigen::VectorXd distances_to_surface(const Points& points, const TriangleSurface& surface);

} // namespace ligsim::tetmesh
