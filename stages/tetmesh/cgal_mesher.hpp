#pragma once
/// @brief The one translation unit that instantiates CGAL Mesh_3 (slow to compile: keep it alone).

#include "common/mesh.hpp"
#include "stages/tetmesh/tetmesh.hpp"

namespace ligsim::tetmesh {

/// Runs Mesh_3 on the volume bounded by `surface` (already checked closed) with sizes already
/// resolved (all > 0), then perturbation and exudation as asked. Returns the cells in the
/// complex with their vertices renumbered compactly, in CGAL's (positive) orientation.
TetMesh mesh_with_cgal(const TriangleSurface& surface, const Parameters& resolved);

} // namespace ligsim::tetmesh
