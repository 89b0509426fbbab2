#pragma once
/// @brief The nodes of a tet mesh's boundary and the area each one stands for (a third of the
/// rest area of the boundary triangles around it): where contact acts.

#include "common/mesh.hpp"
#include "sim/mesh/quadratic_tet.hpp"
#include "sim/solver/boundary_conditions.hpp"

#include <Eigen/Core>

#include <vector>

namespace ligsim::sim {

struct ContactSurface {
  std::vector<int> nodes;    ///< increasing
  Eigen::VectorXd areas_mm2; ///< one per entry of `nodes`
  Triangles faces;           ///< the boundary triangles, outward, mesh node indices
};

/// The faces that belong to one tet only, and their nodes. With `tet10` (the mesh's tets with
/// their mid-edge nodes), each face is split into four at its mid-edge nodes: a linear surface
/// through every node of the quadratic one, on which contact acts (the linear proxy of a
/// higher-order surface, as Ferguson et al., ACM Trans Graph 2023;42(4):129, collide it).
ContactSurface boundary_surface(const TetMesh& mesh, const QuadraticTetrahedra* tet10 = nullptr);

/// The boundary without the nodes whose three components `conditions` prescribe (they cannot
/// answer a contact force); the faces stay whole.
ContactSurface free_boundary_surface(const TetMesh& mesh, const BoundaryConditions& conditions,
                                     const QuadraticTetrahedra* tet10 = nullptr);

} // namespace ligsim::sim
