#pragma once
/// @brief The FEBio reference of the paper's cube experiments (data/febio-cube): the case list
/// (cases.json), the shared tet mesh (mesh.txt) and FEBio's nodal displacements per case.

#include "common/mesh.hpp"
#include "sim/material/material_parameters.hpp"

#include <Eigen/Core>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace ligsim::sim {

/// mesh.txt: nodes, positively oriented tets, bottom and top node sets (0-based here).
struct FebioMesh {
  TetMesh mesh;
  std::vector<int> bottom_nodes;
  std::vector<int> top_nodes;
};

/// FEBio's own figures for a case, as cases.json records them (empty where it does not).
struct FebioFigures {
  std::optional<double> wall_s;
  std::optional<double> avg_top_uz_mm; ///< the top face's mean displacement along z
  std::optional<double> volume_change_rel;
};

struct FebioCase {
  std::string name;
  Eigen::Vector3d fiber = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d force_per_top_node_n = Eigen::Vector3d::Zero();
  /// The case's own energy (fiber convention and volumetric law as FEBio ran it).
  MaterialParameters material;
  std::string incompressibility;       ///< "penalty" or "augmented_lagrangian"
  std::filesystem::path displacements; ///< absolute path of <case>.txt
  FebioFigures febio;
};

struct FebioReference {
  std::filesystem::path directory;
  double edge_mm = 1.0;
  std::filesystem::path mesh_file;
  std::vector<FebioCase> cases;
};

/// Reads `directory`/cases.json. Throws InputError naming the file and the field on any
/// missing or malformed entry.
FebioReference read_febio_reference(const std::filesystem::path& directory);

FebioMesh read_febio_mesh(const std::filesystem::path& file);

/// FEBio's final displacements (#nodes x 3, mm) from a `node_id ux uy uz` file.
Points read_febio_displacements(const std::filesystem::path& file, Eigen::Index node_count);

} // namespace ligsim::sim
