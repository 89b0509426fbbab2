#pragma once
/// @brief The model-building stages as a graph of files: what each reads, writes and depends on,
/// and the cache that reruns a stage only when its inputs or parameters changed.

#include "pipeline/stage_graph/build_config.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace ligsim {
class RunSummary;
}

namespace ligsim::pipeline {

struct Stage {
  std::string name;                 ///< also the subcommand
  std::string description;          ///< one line for --help
  std::vector<std::string> depends; ///< upstream stages, whose outputs it reads
  std::vector<std::string> outputs; ///< files it writes in the output folder
  /// User files it reads (surfaces), from the config.
  std::function<std::vector<std::filesystem::path>(const BuildConfig&)> user_inputs;
  /// Runs the stage: reads its inputs, writes its outputs into `dir`, returns its figures.
  std::function<nlohmann::json(const BuildConfig&, const std::filesystem::path& dir)> run;
};

/// The stages in data-flow order.
const std::vector<Stage>& build_stages();

/// Where the record of `stage`'s last run in `dir` is kept (its key, figures and time).
std::filesystem::path stage_cache_file(const std::filesystem::path& dir, const std::string& stage);

/// What became of a stage in a run.
enum class StageStatus { ran, reused };

/// Runs `target` and the stages it needs, in order. A stage is reused (not rerun) when all its
/// outputs exist and the key stored beside them (a hash of the stage's parameters, its user
/// input files and its upstream outputs) is current; `force` reruns them all. Records every
/// stage in `summary` with status "ran" or "reused", and returns each stage's status by name.
std::map<std::string, StageStatus> run_target(const BuildConfig& config,
                                              const std::filesystem::path& dir,
                                              const std::string& target, bool force,
                                              RunSummary& summary);

} // namespace ligsim::pipeline
