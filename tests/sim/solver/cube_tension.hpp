#pragma once
/// The solver tests' load case: unit cube, bottom face fixed, a force on every top node.

#include "common/mesh.hpp"
#include "sim/mesh/node_selection.hpp"
#include "sim/solver/boundary_conditions.hpp"

namespace ligsim::sim::test {

inline BoundaryConditions cube_tension(const TetMesh& mesh, const Eigen::Vector3d& per_node_n)
{
  BoundaryConditions conditions;
  ConstraintSet bottom;
  bottom.name = "bottom";
  bottom.nodes = nodes_on_plane(mesh.V, 2, 0.0, 1e-9);
  conditions.constraints.push_back(bottom);
  NodalLoad load;
  load.name = "top";
  load.nodes = nodes_on_plane(mesh.V, 2, 1.0, 1e-9);
  load.force_per_node_n = per_node_n;
  conditions.loads.push_back(load);
  return conditions;
}

} // namespace ligsim::sim::test
