#include "pipeline/stage_graph/companion_build.hpp"

#include "common/atomic_file.hpp"
#include "common/knee_manifest.hpp"
#include "common/mesh.hpp"
#include "common/progress.hpp"
#include "common/run_summary.hpp"
#include "pipeline/stage_graph/companion_size_search.hpp"
#include "pipeline/stage_graph/stage_files.hpp"
#include "pipeline/stage_graph/stage_graph.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <fstream>
#include <map>
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

/// The tetmesh stage's cache record in `dir`; an empty object without one.
nlohmann::json tetmesh_record(const fs::path& dir)
{
  std::ifstream record(stage_cache_file(dir, "tetmesh"));
  const nlohmann::json stage = nlohmann::json::parse(record, nullptr, false);
  return stage.is_object() ? stage : nlohmann::json::object();
}

/// The figures of the tetmesh stage's cache record in `dir`; an empty object without one.
nlohmann::json tetmesh_figures(const fs::path& dir)
{
  return tetmesh_record(dir).value("figures", nlohmann::json::object());
}

/// The mean element size of the mesh of the tetmesh stage in `dir`; NaN without a record.
double element_size(const fs::path& dir)
{
  const nlohmann::json figures = tetmesh_figures(dir);
  if (!figures.contains("tets") || !figures.contains("total_volume_mm3"))
    return NAN;
  return mean_element_size(figures.at("total_volume_mm3").get<double>(),
                           figures.at("tets").get<double>());
}

/// `config` with the tetmesh sizes the model's tetmesh stage used (its record in `dir`, where the
/// defaults from the surface's thickness are resolved) times `scale`.
BuildConfig coarser(const BuildConfig& config, const fs::path& dir, double scale)
{
  BuildConfig companion = config;
  tetmesh::Parameters& sizes = companion.tetmesh;
  const nlohmann::json used = tetmesh_figures(dir).value("used", nlohmann::json());
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

/// The cache key of the model's tetmesh stage in `dir`: what the companion's sizes derive from.
std::string model_mesh_key(const fs::path& dir)
{
  return tetmesh_record(dir).value("key", "");
}

/// The factor the previous build's companion took (its summary.json in `dir`) where it was
/// searched for the model's mesh as it is now, else `target`: a factor found for other sizes would
/// start the search elsewhere than a fresh build does and could end elsewhere. A factor must
/// exceed 1 (the search divides by its logarithm).
double previous_scale(const fs::path& dir, double target)
{
  std::ifstream file(dir / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(file, nullptr, false);
  if (!summary.is_object() || !summary.contains("results") ||
      !summary["results"].contains("companion") || !summary["results"]["companion"].is_object())
    return target;
  const nlohmann::json& companion = summary["results"]["companion"];
  const nlohmann::json scale = companion.value("sizes_scaled_by", nlohmann::json());
  if (companion.value("model_mesh_key", "") != model_mesh_key(dir) || !scale.is_number() ||
      !(scale.get<double>() > 1.0))
    return target;
  return scale.get<double>();
}

/// How the companion's mesh came out: its config, and the search that sized it.
struct CompanionMesh {
  BuildConfig config;
  SizeSearch search;
};

/// Builds the companion model in `building` (the tetmesh, fibers and model stages) until its
/// elements are `target` times the model's in size (search_size_factor; Celik et al. 2008 ask at
/// least 1.3 of the estimate). Sizes too coarse for the ligament fail as a mesh or as a model (no
/// node on a footprint) and are backed off from. The first try takes the factor the previous
/// build's companion took, so an unchanged rebuild runs nothing.
CompanionMesh build_to_size_ratio(const BuildConfig& config, const fs::path& dir,
                                  const fs::path& building, double target, bool force,
                                  RunSummary& own)
{
  const double model_size = element_size(dir);
  CompanionMesh mesh;
  mesh.search = search_size_factor(previous_scale(dir, target), target, [&](double scale) {
    mesh.config = coarser(config, dir, scale);
    const std::map<std::string, StageStatus> statuses =
        run_target(mesh.config, building, "model", force, own);
    const bool reused = std::all_of(kRemeshed.begin(), kRemeshed.end(), [&](const auto& stage) {
      return statuses.count(stage) && statuses.at(stage) == StageStatus::reused;
    });
    return SizeTry{element_size(building) / model_size, reused};
  });
  return mesh;
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
  log_info(fmt::format(
      "companion: the model meshed with elements {:g} times as large, for the flexion's "
      "error estimate",
      scale));
  RunSummary own("build");
  CompanionMesh mesh;
  // Built aside from the old companion's files (hard links: its current stages are reused) and
  // put in its place when complete.
  const fs::path building = dir / (temporary_prefix() + std::to_string(::getpid()));
  try {
    if (fs::exists(companion))
      fs::copy(companion, building,
               fs::copy_options::recursive | fs::copy_options::create_hard_links);
    share_upstream_stages(dir, building);
    mesh = build_to_size_ratio(config, dir, building, scale, force, own);
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
  summary.results()["companion"] = {{"built", true},
                                    {"folder", companion_model_folder},
                                    {"mesh_scale", scale},
                                    {"size_ratio", mesh.search.size_ratio},
                                    {"sizes_scaled_by", mesh.search.scale},
                                    {"meshings", mesh.search.meshings},
                                    {"model_mesh_key", model_mesh_key(dir)}};
  if (mesh.search.size_ratio < companion_min_size_ratio)
    log_info(fmt::format("companion: its elements are only {:.2f} times the model's after {} "
                         "meshings; ligsim flexion will say its estimate is not reliable",
                         mesh.search.size_ratio, mesh.search.meshings));
}

} // namespace ligsim::pipeline
