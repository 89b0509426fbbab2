#pragma once
/// @brief The one translation unit that instantiates CGAL Mesh_3 (slow to compile: keep it alone).

#include "common/mesh.hpp"
#include "stages/tetmesh/tetmesh.hpp"

namespace ligsim::tetmesh {

/// Runs Mesh_3 on the volume bounded by `surface` (already checked closed) with sizes already
/// resolved (all > 0), keeping `features` (curves on the surface) as chains of mesh edges at
/// most `feature_edge_mm` long, then
/// perturbation and exudation as asked. Returns the cells in the
/// complex with their vertices renumbered compactly, in CGAL's (positive) orientation.
TetMesh mesh_with_cgal(const TriangleSurface& surface, const std::vector<FeatureLine>& features,
                       double feature_edge_mm, const Parameters& resolved);

} // namespace ligsim::tetmesh
