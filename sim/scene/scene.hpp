#pragma once
/// @brief A simulation scene: mesh, material, fibers, node sets, boundary conditions, loads,
/// solver and outputs, read from a TOML file (every key: docs/simulate.md).

#include "common/mesh.hpp"
#include "sim/contact/contact_config.hpp"
#include "sim/material/material_parameters.hpp"
#include "sim/solver/boundary_conditions.hpp"
#include "sim/solver/hyperelastic_body.hpp"
#include "sim/solver/implicit_euler.hpp"
#include "sim/solver/static_solver.hpp"

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace ligsim::sim {

enum class SceneKind { quasi_static, dynamic };

struct OutputSettings {
  int every = 1;   ///< write a VTU every N load steps or frames (the last one always)
  bool vtu = true; ///< false: summary.json and reactions.csv only
};

/// A rigid bone for contact: its surface, moved with a [[rigid]] set (or fixed).
struct SceneBone {
  std::string name;
  std::filesystem::path surface;
  std::string follows; ///< a [[rigid]] set's name, or "" for a fixed bone
};

struct Scene {
  std::filesystem::path file; ///< the scene file ("" when parsed from text)
  std::string mesh_source;    ///< "file <path>" or the generator and its parameters
  TetMesh mesh;               ///< the tets, or the corners of 10-node ones
  QuadraticTetrahedra tet10;  ///< the 10-node tets of a model.vtu of them, over mesh.V
  MaterialParameters material;
  FiberField fibers; ///< empty without fibers
  std::map<std::string, std::vector<int>> node_sets;
  BoundaryConditions conditions;
  SceneKind kind = SceneKind::quasi_static;
  NewtonSettings newton;
  DynamicsSettings dynamics;
  OutputSettings output;
  ContactConfig contact; ///< used when `bones` is not empty and contact is not turned off
  std::vector<SceneBone> bones;
};

/// Reads a scene file, with `overrides` ("table.key=value", the command line's --set) over it;
/// relative paths in it are relative to the file's folder. Throws InputError naming the file (or
/// the --set), the table and the key of the first problem.
Scene load_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});

/// The same from TOML text; `base` resolves relative paths, `name` labels errors.
Scene parse_scene(const std::string& text, const std::filesystem::path& base,
                  const std::string& name);

} // namespace ligsim::sim
