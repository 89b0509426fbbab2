#pragma once
/// @brief knee.json: what a knee model folder holds. `ligsim build` writes it beside the shared
/// bones (femur.vtp, tibia.vtp, fibula.vtp) and one folder per ligament; `ligsim flexion` and the
/// studies read it. A folder without it is a one-ligament model.

#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace ligsim {

/// One ligament of the knee.
struct KneeLigament {
  std::string name;            ///< e.g. "ACL"
  std::string folder;          ///< its model folder, relative to the knee folder
  std::string distal_bone;     ///< "tibia" or "fibula": the bone of its distal footprint
  double in_situ_strain = 0.0; ///< fiber pre-strain it was built with
  double failure_strain = 0.0; ///< fiber strain (stretch - 1) where it fails
  double failure_load_n = 0.0; ///< N
  /// Weiss material, in a flexion config's [material] keys: mu_mpa, k_mpa, volumetric, c3_mpa,
  /// c4, c5_mpa, lambda_star, convention.
  nlohmann::json material = nlohmann::json::object();
  std::string defaults_source;            ///< where its material and failure figures come from
  std::vector<std::string> contact_bones; ///< the bones it meets by contact (empty: every bone)
};

struct KneeManifest {
  std::vector<KneeLigament> ligaments;
  std::map<std::string, std::string> bones; ///< bone name -> surface file in the knee folder
};

inline constexpr const char* knee_manifest_file = "knee.json";
/// A ligament's folder keeps, in this folder, the same ligament meshed coarser: the companion
/// model `ligsim flexion` estimates its discretisation error with.
inline constexpr const char* companion_model_folder = "companion";
/// The least ratio of the companion's element size to the model's that a two-mesh estimate
/// stands on: below it the two meshes' difference is too close to their noise (Celik et al.,
/// J Fluids Eng 2008;130:078001).
inline constexpr double companion_min_size_ratio = 1.3;

nlohmann::json to_json(const KneeManifest& manifest);
/// Throws InputError naming `where` on a malformed document (a missing key, a ligament without
/// name or folder, a distal bone other than tibia or fibula, two ligaments of one name).
KneeManifest knee_manifest_from_json(const nlohmann::json& json, const std::string& where);
/// The manifest of `dir`, or none when the folder has no knee.json.
std::optional<KneeManifest> read_knee_manifest(const std::filesystem::path& dir);

} // namespace ligsim
