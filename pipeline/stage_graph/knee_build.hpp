#pragma once
/// @brief Building a knee: every ligament through its own stage graph in its own folder (its own
/// cache: changing one ligament's settings reruns that ligament's stages only), and the knee's
/// folder around them: the shared bones, the knee's anatomy and knee.json.

#include "pipeline/stage_graph/knee_config.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

namespace ligsim {
class RunSummary;
}

namespace ligsim::pipeline {

/// Runs `target` and the stages it needs for every ligament of `knee`, in <dir>/<name>/ (each
/// with its own summary.json), records each ligament's stages in `summary` as "<name>/<stage>"
/// and, when `target` is "model", writes the knee's files in `dir` (write_knee_files).
void build_knee(const KneeConfig& knee, const std::filesystem::path& dir, const std::string& target,
                bool force, RunSummary& summary);

/// `knee` with its anatomy found once, from all its parts (knee_anatomy of its shared config),
/// and given to every ligament (BuildConfig::anatomy.known), as build_knee builds it.
KneeConfig with_knee_anatomy(const KneeConfig& knee);

/// One ligament of `knee` as build_knee builds it: its stages in <dir>/<name>/ with its own
/// summary.json, recorded in `summary` as "<name>/<stage>". Throws what the stages throw.
void build_knee_ligament(const KneeConfig& knee, const LigamentConfig& ligament,
                         const std::filesystem::path& dir, const std::string& target, bool force,
                         RunSummary& summary);

/// The knee's own files in `dir`: femur.vtp, tibia.vtp, fibula.vtp (if given), anatomy.json and
/// knee.json, which lists the ligaments of `knee` (each built in <dir>/<name>/).
void write_knee_files(const KneeConfig& knee, const std::filesystem::path& dir);

/// Every parameter of the knee, as JSON (summary.json): per ligament as to_json(BuildConfig).
nlohmann::json to_json(const KneeConfig& knee);

} // namespace ligsim::pipeline
