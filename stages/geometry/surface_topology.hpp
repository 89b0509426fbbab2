#pragma once
/// @brief Is a triangle surface a closed, consistently oriented 2-manifold? Where is it not?

#include "common/mesh.hpp"

#include <Eigen/Core>

#include <utility>
#include <vector>

namespace ligsim {

struct TopologyReport {
  int boundary_edges = 0;       ///< edges with one triangle: holes in the surface
  int nonmanifold_edges = 0;    ///< edges with three or more triangles
  int inconsistent_edges = 0;   ///< edges whose two triangles run it the same way
  int degenerate_triangles = 0; ///< repeated vertex indices or zero area
  std::vector<Eigen::Vector3d> boundary_edge_midpoints;   ///< a few of them, to say where, mm
  Eigen::Vector3d boundary_min = Eigen::Vector3d::Zero(); ///< bounding box of the boundary edges
  Eigen::Vector3d boundary_max = Eigen::Vector3d::Zero();
  std::vector<std::pair<int, int>> nonmanifold_edge_list;  ///< a few of them (vertex indices)
  std::vector<std::pair<int, int>> inconsistent_edge_list; ///< a few of them (vertex indices)

  bool closed_manifold() const
  {
    return boundary_edges == 0 && nonmanifold_edges == 0 && inconsistent_edges == 0;
  }
};

TopologyReport check_topology(const TriangleSurface& surface);

/// Signed enclosed volume (positive for outward-facing triangles), mm^3.
double signed_volume(const TriangleSurface& surface);

/// Total triangle area, mm^2.
double surface_area(const TriangleSurface& surface);

} // namespace ligsim
