#pragma once
/// @brief A tet mesh from a .vtu file with its named point and cell arrays, as the
/// model-building pipeline writes it (VTK_TETRA or VTK_QUADRATIC_TETRA cells, points in mm).

#include "common/mesh.hpp"

#include <Eigen/Core>

#include <filesystem>
#include <map>
#include <string>

namespace ligsim::sim {

struct VtuMesh {
  TetMesh mesh;              ///< the tets, or the corners of 10-node ones
  QuadraticTetrahedra tet10; ///< the 10-node tets over mesh.V; empty for linear ones
  /// Every point / cell data array, by name: #points (#cells) x components.
  std::map<std::string, Eigen::MatrixXd> point_data;
  std::map<std::string, Eigen::MatrixXd> cell_data;
};

/// Throws InputError naming the file and the first cell that is not a tetrahedron of the kind
/// of the first.
VtuMesh read_vtu_mesh(const std::filesystem::path& file);

} // namespace ligsim::sim
