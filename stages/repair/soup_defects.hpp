#pragma once
/// @brief Finding the defects of a triangle soup that need no halfedge structure: coincident
/// vertices (merged here), degenerate and duplicated triangles (removed here), non-manifold edges
/// and vertices (only located here).

#include "stages/repair/repair.hpp"

#include <array>
#include <vector>

namespace ligsim::repair {

using Soup = std::vector<std::array<int, 3>>;

/// Points every triangle corner at the first vertex of the same coordinates; counts the
/// vertices so merged into an earlier one.
Repair merge_duplicate_vertices(const Points& V, Soup& triangles);

/// Removes triangles with a repeated vertex or zero area.
Repair remove_degenerate(const Points& V, Soup& triangles);

/// Removes every copy but the first of a triangle (same three vertices, either orientation).
Repair remove_duplicates(const Points& V, Soup& triangles);

/// Edges shared by three or more triangles, with their two vertices.
Repair find_nonmanifold_edges(const Points& V, const Soup& triangles);

/// Vertices (not on a non-manifold edge) whose triangles form two or more separate fans.
Repair find_nonmanifold_vertices(const Points& V, const Soup& triangles);

/// Edges whose two triangles run them the same way.
Repair find_inconsistent_edges(const Points& V, const Soup& triangles);

/// Keeps the first few locations of a repair.
void add_location(Repair& repair, const Location& location);

} // namespace ligsim::repair
