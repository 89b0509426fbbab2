#pragma once
/// @brief Every parameter of `ligsim build`, from a TOML config file and command-line flags.

#include "common/knee_anatomy.hpp"
#include "sim/material/material_parameters.hpp"
#include "stages/attachments/attachments.hpp"
#include "stages/centerline/centerline.hpp"
#include "stages/fibers/fibers.hpp"
#include "stages/field/field.hpp"
#include "stages/model/model.hpp"
#include "stages/tetmesh/tetmesh.hpp"
#include "stages/voxelize/voxelize.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace ligsim::pipeline {

/// The knee flexion the model's scene prescribes: the femur nodes rotate about a flexion axis
/// while the tibia nodes stay fixed.
struct FlexionDefaults {
  double max_angle_deg = 90.0;
  int steps = 6;
  /// The axis; when not given (`axis_given` false) the model stage picks the line through the
  /// femoral attachment along the ligament's thinnest principal direction (for a collateral
  /// ligament, the mediolateral direction: close to the transepicondylar axis).
  bool axis_given = false;
  Eigen::Vector3d axis_point_mm = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis_direction = Eigen::Vector3d::UnitX();
};

/// What the config says of the knee's anatomy (written, with what the data adds, into
/// anatomy.json). Directions of zero length and non-finite landmarks are "not given"; a landmark
/// surface stands for its area-weighted centroid.
struct AnatomyInputs {
  std::string side; ///< "left", "right" or empty
  Eigen::Vector3d proximal = Eigen::Vector3d::Zero();
  Eigen::Vector3d posterior = Eigen::Vector3d::Zero();
  Eigen::Vector3d medial_epicondyle_mm = Eigen::Vector3d::Constant(NAN);
  Eigen::Vector3d lateral_epicondyle_mm = Eigen::Vector3d::Constant(NAN);
  std::string medial_epicondyle_surface; ///< a surface file (resolved against the config)
  std::string lateral_epicondyle_surface;
  /// Further parts the anatomy is read off (not config keys: the build sets them), by their
  /// part names (anatomy::part_name): the knee's "tibia" (when the ligament's own distal bone is
  /// the fibula), "fibula" and "patella", and its ligaments
  /// ("MCL", "LCL", ...) for the side and the epicondyles.
  std::map<std::string, std::filesystem::path> parts;
  /// The knee's anatomy, found once for all its ligaments (a knee build sets it): the anatomy
  /// stage writes it as it is.
  std::optional<KneeAnatomy> known;
};

/// The companion model `ligsim flexion` estimates its discretisation error with: the same ligament
/// meshed with elements `mesh_scale` times as large ((volume / tets)^(1/3); its cell and facet
/// sizes and facet distance scaled until they are), built beside the model in its folder's
/// companion/ (companion_build.hpp). 0: no companion, no estimate.
struct ErrorEstimateParameters {
  double mesh_scale = 1.5;
};

struct BuildConfig {
  std::filesystem::path surface; ///< ligament surface (required)
  std::filesystem::path femur;   ///< optional
  std::filesystem::path tibia;   ///< optional
  /// Refuse a defective ligament surface instead of repairing it.
  bool strict = false;
  /// A segmentation label map to take the surfaces from (instead of surface/femur/tibia), and
  /// the labels (numbers or names, as text) of the ligament and, optionally, the bones. Names
  /// resolve through the map's segment names and a colour table (`colour_table`, or one beside
  /// the map).
  std::filesystem::path labels;
  std::filesystem::path colour_table;
  std::string ligament_label, femur_label, tibia_label;
  /// The surfaces came from a label map in a scanner's LPS frame, whose axes give proximal (+S)
  /// and posterior (+P); false for a map made from surfaces (`ligsim labelmap`), whose axes are
  /// the surfaces'.
  bool label_frame_anatomical = false;
  AnatomyInputs anatomy;
  attachments::Rule femur_attachment;
  attachments::Rule tibia_attachment;
  voxelize::Parameters voxelize;
  centerline::Parameters centerline;
  field::Parameters field;
  tetmesh::Parameters tetmesh;
  fibers::Parameters fibers;
  model::Parameters model;
  /// The Weiss material written into the model's scene; the MCL of the paper's section 4.2
  /// unless the config or the ligament's name gives another.
  sim::MaterialParameters material = sim::mcl_material();
  FlexionDefaults flexion;
  ErrorEstimateParameters error_estimate;
  /// The ligament's part, when its name (its label's, in a label map) is one that
  /// anatomy::recognise_part knows: "MCL", "LCL", "ACL", "PCL"; empty otherwise.
  std::string ligament_part;
  /// The sections the config file or the flags gave ("material", "attachments.femur",
  /// "attachments.tibia"): a recognised ligament's defaults fill the others.
  std::set<std::string> given;
};

/// The ligament part a surface path names, by its glTF mesh name (`knee.glb#VH_F_left_tibial_
/// collateral_ligament`) or else its file's stem: "MCL", "LCL", "ACL", "PCL", or "" (not one).
std::string part_of_surface(const std::filesystem::path& surface);

/// Fills what `config.given` lacks with the defaults of `config.ligament_part` (material,
/// footprints); returns where they come from, or nothing when the part has none.
std::string apply_part_defaults(BuildConfig& config);

/// Reads a TOML config (every key: docs/build.md) with `overrides` ("table.key=value", the
/// command line's --set) over it; no file: the overrides alone. Relative paths are relative to
/// the file's folder. Throws InputError with the file, line and key (or the --set) on a syntax
/// error, an unknown key or a value of the wrong type.
BuildConfig load_build_config(const std::filesystem::path& file,
                              const std::vector<std::string>& overrides = {});

/// The Weiss material under its config keys ([material] of build and flexion configs), as
/// summary.json, knee.json and the stage cache key hold it.
nlohmann::json material_json(const sim::MaterialParameters& material);

/// The parameters one stage depends on, as JSON (for summary.json and the cache key).
nlohmann::json stage_parameters(const BuildConfig& config, const std::string& stage);

/// Every parameter, as JSON.
nlohmann::json to_json(const BuildConfig& config);

} // namespace ligsim::pipeline
