#pragma once
/// @brief The nodes of a tet mesh's boundary and the area each one stands for (a third of the
/// rest area of the boundary triangles around it): where contact acts.

#include "common/mesh.hpp"
#include "sim/solver/boundary_conditions.hpp"

#include <Eigen/Core>

#include <vector>

namespace ligsim::sim {

struct ContactSurface {
  std::vector<int> nodes;    ///< increasing
  Eigen::VectorXd areas_mm2; ///< one per entry of `nodes`
  Triangles faces;           ///< the boundary triangles, outward, mesh node indices
};

/// The faces that belong to one tet only, and their nodes.
ContactSurface boundary_surface(const TetMesh& mesh);

/// The boundary without the nodes whose three components `conditions` prescribe (they cannot
/// answer a contact force); the faces stay whole.
ContactSurface free_boundary_surface(const TetMesh& mesh, const BoundaryConditions& conditions);

} // namespace ligsim::sim
