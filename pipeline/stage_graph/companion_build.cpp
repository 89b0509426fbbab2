#include "pipeline/stage_graph/companion_build.hpp"

#include "common/atomic_file.hpp"
#include "common/knee_manifest.hpp"
#include "common/progress.hpp"
#include "common/run_summary.hpp"
#include "pipeline/stage_graph/stage_files.hpp"
#include "pipeline/stage_graph/stage_graph.hpp"

#include <fmt/format.h>

#include <exception>
#include <fstream>
#include <set>
#include <string>
#include <system_error>

#include <fcntl.h>
#include <stdio.h>
#include <unistd.h>

namespace ligsim::pipeline {

namespace fs = std::filesystem;

namespace {

/// The stages the companion reruns; the others it takes from the model's folder.
const std::set<std::string> kRemeshed = {"tetmesh", "fibers", "model"};

/// `from` at `to`: a hard link where the file system allows one, else a copy; made as an
/// AtomicFile, so that a run killed halfway leaves the old file or the new one.
void link_or_copy(const fs::path& from, const fs::path& to)
{
  AtomicFile file(to);
  // Already a link of it (reused from the old companion): rename() of a link onto a link of the
  // same file does nothing, and would leave the temporary behind.
  std::error_code not_there;
  if (fs::equivalent(from, to, not_there))
    return;
  std::error_code error;
  fs::create_hard_link(from, file.temp_path(), error);
  if (error)
    fs::copy_file(from, file.temp_path(), fs::copy_options::overwrite_existing);
  file.commit();
}

/// The model's upstream outputs and their cache records in `companion`, so that its own build
/// finds them current.
void share_upstream_stages(const fs::path& dir, const fs::path& companion)
{
  ensure_directory(companion / ".ligsim-cache");
  for (const Stage& stage : build_stages()) {
    if (kRemeshed.count(stage.name) || !fs::exists(stage_cache_file(dir, stage.name)))
      continue;
    for (const std::string& output : stage.outputs)
      if (fs::exists(dir / output))
        link_or_copy(dir / output, companion / output);
    link_or_copy(stage_cache_file(dir, stage.name), stage_cache_file(companion, stage.name));
  }
}

/// The hidden temporaries a removed companion passes through: ".companion.tmp-<pid>".
std::string temporary_prefix()
{
  return std::string(".") + companion_model_folder + ".tmp-";
}

/// Removes what earlier runs, killed while removing a companion, left.
void remove_temporaries(const fs::path& dir)
{
  std::error_code ignored;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir, ignored))
    if (entry.path().filename().string().rfind(temporary_prefix(), 0) == 0)
      fs::remove_all(entry.path(), ignored);
}

/// Puts the companion built in `building` in the place of `companion`: one exchange of the two
/// folders (renameat2 RENAME_EXCHANGE), so that a run killed at any moment leaves the old
/// companion whole or the new one; where the file system cannot exchange, the old one is moved
/// aside first. The old one is left at `building`, a temporary.
void put_in_place(const fs::path& building, const fs::path& companion)
{
  if (fs::exists(companion) &&
      ::renameat2(AT_FDCWD, building.c_str(), AT_FDCWD, companion.c_str(), RENAME_EXCHANGE) == 0)
    return;
  const fs::path aside = building.string() + "-old";
  if (fs::exists(companion))
    fs::rename(companion, aside);
  fs::rename(building, companion);
}

/// Removes the companion folder, first renamed to a temporary, so that a run killed halfway
/// leaves the whole companion or none.
void remove_companion(const fs::path& dir)
{
  std::error_code ignored;
  if (fs::exists(dir / companion_model_folder))
    fs::rename(dir / companion_model_folder,
               dir / (temporary_prefix() + std::to_string(::getpid())), ignored);
  remove_temporaries(dir);
}

/// `config` with the tetmesh sizes the model's tetmesh stage used (its record in `dir`, where the
/// defaults from the surface's thickness are resolved) times `scale`.
BuildConfig coarser(const BuildConfig& config, const fs::path& dir, double scale)
{
  BuildConfig companion = config;
  tetmesh::Parameters& sizes = companion.tetmesh;
  std::ifstream record(stage_cache_file(dir, "tetmesh"));
  const nlohmann::json stage = nlohmann::json::parse(record, nullptr, false);
  const nlohmann::json used =
      stage.is_object()
          ? stage.value("figures", nlohmann::json::object()).value("used", nlohmann::json())
          : nlohmann::json();
  if (used.is_object()) {
    sizes.cell_size_mm = used.at("cell_size_mm").get<double>();
    sizes.facet_size_mm = used.at("facet_size_mm").get<double>();
    sizes.facet_distance_mm = used.at("facet_distance_mm").get<double>();
  } else {
    sizes = tetmesh::default_sizes(load_ligament(config), config.tetmesh);
  }
  sizes.cell_size_mm *= scale;
  sizes.facet_size_mm *= scale;
  sizes.facet_distance_mm *= scale;
  companion.error_estimate.mesh_scale = 0.0;
  return companion;
}

} // namespace

void build_companion(const BuildConfig& config, const fs::path& dir, bool force,
                     RunSummary& summary)
{
  const fs::path companion = dir / companion_model_folder;
  const double scale = config.error_estimate.mesh_scale;
  remove_temporaries(dir);
  if (scale <= 0.0) {
    remove_companion(dir);
    return;
  }
  log_info(fmt::format("companion: the model meshed {:g} times coarser, for the flexion's error "
                       "estimate",
                       scale));
  RunSummary own("build");
  // Built aside from the old companion's files (hard links: its current stages are reused) and
  // put in its place when complete.
  const fs::path building = dir / (temporary_prefix() + std::to_string(::getpid()));
  try {
    const BuildConfig coarse = coarser(config, dir, scale);
    if (fs::exists(companion))
      fs::copy(companion, building,
               fs::copy_options::recursive | fs::copy_options::create_hard_links);
    share_upstream_stages(dir, building);
    run_target(coarse, building, "model", force, own);
    put_in_place(building, companion);
    remove_temporaries(dir);
  } catch (const std::exception& error) { // CGAL's too: the model stands without a companion
    std::error_code ignored;
    fs::remove_all(building, ignored);
    remove_companion(dir);
    log_info(fmt::format("companion: not built ({}); ligsim flexion will report no error "
                         "estimate for this model",
                         error.what()));
    summary.results()["companion"] = {{"built", false}, {"reason", error.what()}};
    return;
  }
  for (const auto& [stage, entry] : own.json()["stages"].items())
    if (kRemeshed.count(stage))
      summary.stage("companion/" + stage) = entry;
  summary.results()["companion"] = {
      {"built", true}, {"folder", companion_model_folder}, {"mesh_scale", scale}};
}

} // namespace ligsim::pipeline
