#include "pipeline/stage_graph/stage_graph.hpp"

#include "common/atomic_file.hpp"
#include "common/content_hash.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "common/resources.hpp"
#include "common/run_summary.hpp"
#include "stages/io/surface_path.hpp"

#include <fstream>
#include <set>
#include <system_error>

namespace ligsim::pipeline {

namespace fs = std::filesystem;

namespace {

/// Bumped when a stage's algorithm changes, so old caches are not trusted (2: OpenVDB voxelize;
/// 3: sparse grids passed between the stages as .vdb files; 4: bones repaired into one closed
/// shell; 6: a proximity footprint takes the ligament inside a closed bone).
constexpr const char* kAlgorithmVersion = "ligsim-build-6";

const Stage& find_stage(const std::string& name)
{
  for (const Stage& stage : build_stages())
    if (stage.name == name)
      return stage;
  fail("unknown stage '{}'", name);
}

/// `target` and its transitive dependencies, in data-flow order.
std::vector<const Stage*> plan(const std::string& target)
{
  std::set<std::string> needed;
  std::vector<std::string> open{target};
  while (!open.empty()) {
    const std::string name = open.back();
    open.pop_back();
    if (needed.insert(name).second)
      for (const std::string& upstream : find_stage(name).depends)
        open.push_back(upstream);
  }
  std::vector<const Stage*> order;
  for (const Stage& stage : build_stages())
    if (needed.count(stage.name))
      order.push_back(&stage);
  return order;
}

std::string stage_key(const Stage& stage, const BuildConfig& config, const fs::path& dir)
{
  ContentHash hash;
  hash.add(kAlgorithmVersion).add(stage.name).add(stage_parameters(config, stage.name).dump());
  // A glTF input hashes the whole file and the mesh chosen in it (`knee.glb#femur`).
  for (const fs::path& input : stage.user_inputs(config)) {
    const io::SurfacePath source = io::split_surface_path(input);
    hash.add(source.file.filename().string());
    if (!source.mesh.empty())
      hash.add("#" + source.mesh);
    hash.add_file(source.file);
  }
  for (const std::string& upstream : stage.depends)
    for (const std::string& output : find_stage(upstream).outputs)
      hash.add(output).add_file(dir / output);
  return hash.hex();
}

nlohmann::json read_cache(const fs::path& file)
{
  std::ifstream in(file);
  if (!in)
    return nullptr;
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception&) {
    return nullptr; // a damaged cache entry only means the stage reruns
  }
}

} // namespace

fs::path stage_cache_file(const fs::path& dir, const std::string& stage)
{
  return dir / ".ligsim-cache" / (stage + ".json");
}

std::map<std::string, StageStatus> run_target(const BuildConfig& config, const fs::path& dir,
                                              const std::string& target, bool force,
                                              RunSummary& summary)
{
  std::map<std::string, StageStatus> statuses;
  ensure_directory(dir);
  ensure_directory(dir / ".ligsim-cache");
  for (const Stage* stage : plan(target)) {
    const std::string key = stage_key(*stage, config, dir);
    const nlohmann::json cached = read_cache(stage_cache_file(dir, stage->name));
    bool current = !force && cached.is_object() && cached.value("key", "") == key;
    for (const std::string& output : stage->outputs)
      current = current && fs::exists(dir / output);
    nlohmann::json& entry = summary.stage(stage->name);
    entry["parameters"] = stage_parameters(config, stage->name);
    if (current) {
      log_info(fmt::format("{}: current, reused", stage->name));
      entry["status"] = "reused";
      entry["figures"] = cached["figures"];
      entry["wall_s"] = 0.0;
      entry["previous_wall_s"] = cached.value("wall_s", 0.0);
      entry["previous_peak_rss_mib"] = cached.value("peak_rss_mib", 0.0);
      statuses[stage->name] = StageStatus::reused;
      continue;
    }
    log_info(fmt::format("{}: {}", stage->name, stage->description));
    // The old record goes before the first output is replaced: a run killed halfway through the
    // stage leaves no record, so a later run never takes a mix of old and new outputs as the
    // old parameters' result.
    std::error_code ignored;
    fs::remove(stage_cache_file(dir, stage->name), ignored);
    const StageMeter meter;
    nlohmann::json figures = stage->run(config, dir);
    summary.add_stage(stage->name, meter, {{"status", "ran"}, {"figures", figures}});
    const nlohmann::json record = {{"key", key},
                                   {"figures", figures},
                                   {"wall_s", meter.wall_s()},
                                   {"peak_rss_mib", meter.peak_rss_mib()}};
    write_text_atomically(stage_cache_file(dir, stage->name), record.dump(2) + "\n");
    statuses[stage->name] = StageStatus::ran;
  }
  return statuses;
}

} // namespace ligsim::pipeline
