#pragma once
/// @brief A tearing scene: mesh, material, fibers, criterion, solver, boundary conditions,
/// loads, initial cuts and run limits, as read from a TOML file (every key: docs/tear.md).

#include "sim/membrane/crack/tearing.hpp"
#include "sim/membrane/mesh/membrane_mesh.hpp"
#include "sim/membrane/model/implicit_euler.hpp"
#include "sim/membrane/model/material.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace ligsim::membrane {

struct MeshSpec {
  enum class Shape { rectangle, disc } shape = Shape::rectangle;
  double width_mm = 0.0, height_mm = 0.0; ///< rectangle, centred on the origin
  double radius_mm = 0.0;                 ///< disc, centred on the origin
  double element_size_mm = 0.0;
  double jitter = 0.15; ///< interior nodes move by up to this fraction of the element size
  std::uint64_t seed = 1;
};

struct FiberSpec {
  enum class Kind { uniform, concentric, per_element } kind = Kind::uniform;
  double angle_rad = 0.0;         ///< uniform: from the x axis
  Vec2 centre_mm = Vec2::Zero();  ///< concentric: circles around this point
  std::vector<double> angles_rad; ///< per element, in mesh generation order
};

/// A set of points: inside a box, or outside a circle.
struct Region {
  enum class Kind { box, outside_circle } kind = Kind::box;
  Eigen::Vector4d box_mm = Eigen::Vector4d::Zero(); ///< x_min, y_min, x_max, y_max
  Vec2 centre_mm = Vec2::Zero();
  double radius_mm = 0.0;

  bool contains(const Vec2& p) const;
};

/// Nodes with a prescribed velocity: zero (fixed) unless given.
struct ConstraintSpec {
  Region region;
  Vec2 velocity_mm_per_s = Vec2::Zero();
};

/// A dead load per unit rest length on the boundary sides inside a region, ramped in time:
/// min(rate t, max) along `direction`.
struct TractionSpec {
  Region region;
  Vec2 direction = Vec2::UnitX();
  double rate_n_per_mm_per_s = 0.0;
  double max_n_per_mm = 0.0;
};

/// The capsulorhexis flap: a force on the nodes behind the lead crack tip (the first tip of the
/// first cut), within `radius_mm` of it and on the inner side (nearer to `centre_mm`), along
/// the tear direction turned towards the centre by `inward_rad`; min(rate t, max) in total.
struct GraspSpec {
  Vec2 centre_mm = Vec2::Zero();
  double radius_mm = 0.0;
  double force_rate_n_per_s = 0.0;
  double max_force_n = 0.0;
  double inward_rad = 0.0;
};

struct CutSpec {
  std::vector<Vec2> points_mm;
  bool tear_from_start = true; ///< the start becomes a crack tip (if inside the material)
  bool tear_from_end = true;
};

struct RunSpec {
  int max_steps = 1000;
  int frame_every = 10;
  bool stop_when_separated = true;
  /// Stop once the lead tip has turned this far around `centre_mm` (0: never).
  double stop_after_turn_rad = 0.0;
  /// Where the tear radius is measured from (capsulorhexis), if given.
  std::optional<Vec2> centre_mm;
};

struct Scene {
  std::string name;
  std::filesystem::path source; ///< the file it came from
  MeshSpec mesh;
  MembraneMaterial material;
  FiberSpec fibers;
  TearSettings tearing;
  SolverSettings solver;
  std::vector<ConstraintSpec> fixed;
  std::vector<TractionSpec> tractions;
  std::optional<GraspSpec> grasp;
  std::vector<CutSpec> cuts;
  RunSpec run;
};

/// Reads a scene file, with `overrides` ("table.key=value", the command line's --set) over it.
/// Throws InputError naming the file (and line or key, or the --set) if it is missing, malformed,
/// has an unknown key, or a value is out of range.
Scene load_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});

} // namespace ligsim::membrane
