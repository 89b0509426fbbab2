#pragma once
/// @brief Compression cases of the cube experiment: 0.02 to 0.20 N per top node pushing down,
/// fibers along the load (z) and across it (x), FEBio's penalty energy with each volumetric
/// law. No FEBio solution of them ships with the project (no FEBio on the machine that made
/// this), so they are checked by their equilibrium: the free-DOF residual and the balance of the
/// bottom reactions against the load.

#include "sim/verify/cube_verification.hpp"

#include <string>
#include <vector>

namespace ligsim::sim {

/// The loads per top node, N (pushing down).
std::vector<double> cube_compression_loads_n();

/// The 16 cases, named cmp_<along|across>_<load in cN>_<lnj|jm1>, from the reference's penalty
/// tension cases (their materials); `displacements` is empty.
std::vector<FebioCase> cube_compression_cases(const FebioReference& reference);

/// A cube mesh of n x n x n hexes (5 tets each, the reference mesh at n = 16) with its bottom
/// and top node sets.
FebioMesh structured_cube(int cells, double edge_mm);

} // namespace ligsim::sim
