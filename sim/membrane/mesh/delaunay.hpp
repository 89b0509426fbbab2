#pragma once
/// @brief Delaunay triangulation of points in the plane (Bowyer-Watson), for generating meshes.

#include "sim/membrane/mesh/membrane_mesh.hpp"

#include <vector>

namespace ligsim::membrane {

/// Counter-clockwise Delaunay triangles of `points` (their convex hull). Meant for meshes
/// of up to some thousands of points in general position (O(n^2) time). Throws SolverError
/// if the result does not cover the hull.
std::vector<Triangle> delaunay_triangulation(const std::vector<Vec2>& points);

} // namespace ligsim::membrane
