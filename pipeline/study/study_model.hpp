#pragma once
/// @brief What a study builds: one ligament's build config, or a knee's (every ligament in its
/// own folder, the bones once, as `ligsim build` builds a knee). The studies change each
/// ligament's config the same way and report each ligament on its own.

#include "pipeline/stage_graph/knee_config.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace ligsim::study {

struct StudyModel {
  /// A knee config: built as a knee folder (knee.json); else `config` holds one ligament.
  bool knee = false;
  /// The knee's config, or one ligament's config as the knee's only ligament (its name empty:
  /// the flexion names it, as `ligsim flexion` names a one-ligament model).
  pipeline::KneeConfig config;
};

/// Reads a build config for `job` ("study convergence", ...): a knee's (keeping the ligaments
/// `chosen` names, in the knee's order; all when empty) or one ligament's. Throws InputError
/// naming a ligament the knee does not have (and the ones it has), a name given twice, or a
/// choice of ligaments for a one-ligament config.
StudyModel load_study_model(const std::filesystem::path& file,
                            const std::vector<std::string>& chosen, const std::string& job);

/// The knee's ligaments' names, or for one ligament `single_name`.
std::vector<std::string> ligament_names(const StudyModel& model, const std::string& single_name);

/// A ligament's folder in the built model in `dir`: <dir>/<name> in a knee, else `dir`.
std::filesystem::path ligament_folder(const StudyModel& model, std::size_t ligament,
                                      const std::filesystem::path& dir);

} // namespace ligsim::study
