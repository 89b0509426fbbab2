#pragma once
/// @brief Generated tet meshes for verification and benchmarks: a box of hexes split into five
/// tets each (alternating, so faces match), and the same box bent along an arc.

#include "common/mesh.hpp"

#include <Eigen/Core>

namespace ligsim::sim {

/// Box [0, size.x] x [0, size.y] x [0, size.z] (mm) with cells.x x cells.y x cells.z hexes, each
/// split into 5 positively oriented tets. Node (i, j, k) has index
/// i + (cells.x + 1) (j + (cells.y + 1) k); the central tet of every hex joins the corners whose
/// i + j + k is even. With cells = (16, 16, 16) and size 1 mm this is the FEBio reference mesh.
TetMesh structured_box_mesh(const Eigen::Vector3i& cells, const Eigen::Vector3d& size_mm);

/// The unit-edge-scaled cube with n hexes along each edge.
TetMesh structured_cube_mesh(int n, double edge_mm);

/// A bar of length x width x thickness (mm) along x, bent about the y axis so that its axis
/// turns by `bend_deg` degrees over its length: a ligament-sized test body.
TetMesh bent_bar_mesh(const Eigen::Vector3i& cells, const Eigen::Vector3d& size_mm,
                      double bend_deg);

} // namespace ligsim::sim
