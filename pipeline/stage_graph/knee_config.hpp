#pragma once
/// @brief A knee's build config: the bones once ([input] femur, tibia, fibula), the knee's
/// anatomy, stage sections that every ligament shares, and one [[ligament]] table per ligament
/// whose sections read as a one-ligament config's do (format in docs/knee-model.md).

#include "pipeline/stage_graph/build_config.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace ligsim::pipeline {

/// One ligament of a knee.
struct LigamentConfig {
  std::string name;              ///< its folder in the knee's output and its label, e.g. "ACL"
  std::string distal_bone;       ///< "tibia" or "fibula": where its distal footprint lies
  double failure_strain = 0.171; ///< fiber strain (stretch - 1)
  double failure_load_n = 799.0; ///< N
  std::string defaults_source;   ///< where its material and failure defaults come from
  /// The bones it meets by contact in a flexion (empty: every bone of the knee).
  std::vector<std::string> contact_bones;
  BuildConfig build; ///< its stages; build.tibia is its distal bone's surface
};

struct KneeConfig {
  std::filesystem::path file;
  std::filesystem::path femur, tibia, fibula; ///< fibula optional
  std::filesystem::path patella; ///< optional: only the anatomy reads it (the knee's front)
  /// A segmentation label map instead of surface files: the bones' labels here, each
  /// ligament's in its build.ligament_label (numbers or names, as text); the surfaces are taken
  /// from the map into the knee's output folder by knee_surfaces_from_labels.
  std::filesystem::path labels, colour_table;
  std::string femur_label, tibia_label, fibula_label, patella_label;
  BuildConfig shared; ///< the bones, anatomy and stage sections before any ligament's own
  std::vector<LigamentConfig> ligaments;
};

/// Gives every ligament's anatomy (and the knee's) the parts it is read off: the fibula, the
/// patella, and each ligament whose name anatomy::recognise_part knows (for the side and the
/// epicondyles). Call once the surfaces are where the build reads them.
void add_anatomy_parts(KneeConfig& knee);

/// Whether `file` is a knee config: a TOML file with a `ligament` array of tables.
bool is_knee_config(const std::filesystem::path& file);

/// Reads a knee config (surface files, or a label map with every part's label). Relative paths are
/// relative to the file's folder. Throws InputError with the file, line and key on a syntax error,
/// an unknown key, a value of the wrong type, a ligament without name or surface, two ligaments of
/// one name, or a footprint on a bone the config does not give. `overrides` as for
/// load_build_config (over [[ligament]] tables, they set every ligament).
KneeConfig load_knee_config(const std::filesystem::path& file,
                            const std::vector<std::string>& overrides = {});

} // namespace ligsim::pipeline
