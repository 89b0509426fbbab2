#pragma once
/// @brief The surface of a 10-node tet mesh laid onto the surface it was meshed from: each
/// mid-edge node of a boundary edge moved onto that surface, as far as no element folds.

#include "common/mesh.hpp"

namespace ligsim::sim {

/// What curve_boundary_to_surface did, for the build's report.
struct CurvedBoundary {
  int boundary_mid_nodes = 0; ///< mid-edge nodes of the mesh's boundary edges
  int moved = 0;              ///< moved onto the surface
  int moved_part_way = 0;     ///< moved part way: the whole move would have distorted an element
  int left_straight = 0;      ///< left at their edge's middle for the same reason
  double max_offset_mm = 0.0; ///< the largest distance a node moved
  double max_gap_mm = 0.0;    ///< the largest distance left between a moved node and the surface
  double min_jacobian_ratio = 1.0; ///< over the elements touched (sim::jacobian_ratio)
};

/// The smallest jacobian_ratio an element may be left with: its volume density nowhere below
/// this share of the straight element's, so that curving never makes a poor element.
inline constexpr double kMinCurvedJacobianRatio = 0.5;

/// Moves every mid-edge node of a boundary edge (an edge of a face that belongs to one element)
/// to the point of `surface` nearest it; where that leaves an element around it below
/// kMinCurvedJacobianRatio (at its corners or the points of the degree-5 rule), the move is
/// halved, four times at most, and then not made. Nodes are taken in index order, so the result
/// is deterministic. `mesh` must come from promote_to_quadratic of a mesh of `surface`'s volume.
CurvedBoundary curve_boundary_to_surface(QuadraticTetMesh& mesh, const TriangleSurface& surface);

} // namespace ligsim::sim
