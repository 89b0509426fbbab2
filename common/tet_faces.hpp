#pragma once
/// @brief The boundary of a tetrahedral mesh: the faces that belong to one tet only.

#include "common/mesh.hpp"

#include <array>
#include <vector>

namespace ligsim {

/// The faces of `T` that belong to exactly one tet, each with its corners in the order that
/// makes its normal point out of a positive tet, sorted by their sorted corners.
std::vector<std::array<int, 3>> tet_boundary_faces(const Tetrahedra& T);

} // namespace ligsim
