#pragma once
/// @brief `ligsim build --labels seg.nrrd --out K` with nothing else: a knee config made from
/// the label map's names (its bones and the ligaments ligsim knows, each with the defaults of its
/// name), written as K/knee.toml for the user to read, edit and rebuild.

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

namespace ligsim::pipeline {

struct KneeFromLabels {
  std::string config_text; ///< the knee config (TOML), with comments saying what was found
  /// Per label of the map: its value, names, voxels and what it was taken for ("femur", "MCL",
  /// "not used: cartilage", "not recognised").
  nlohmann::json labels = nlohmann::json::array();
  std::vector<std::string> notes; ///< what could not be found ("no femur: ...")
};

/// Reads the map and its names (`colour_table`, or the one beside the map) and makes the knee's
/// config; paths in it are written relative to `config_dir`, where it will be saved. Throws
/// InputError when no label names a bone, when two labels name one bone or one ligament, when
/// no label names a ligament ligsim builds (MCL, LCL, ACL, PCL), or when there is no tibia.
KneeFromLabels knee_from_labels(const std::filesystem::path& labels,
                                const std::filesystem::path& colour_table,
                                const std::filesystem::path& config_dir);

} // namespace ligsim::pipeline
