#include "pipeline/study/study_runs.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/knee_manifest.hpp"
#include "common/progress.hpp"
#include "common/resources.hpp"
#include "common/run_summary.hpp"
#include "pipeline/stage_graph/knee_build.hpp"
#include "pipeline/stage_graph/stage_graph.hpp"
#include "sim/flexion/knee_flexion.hpp"
#include "sim/flexion/knee_sweep.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <numeric>

namespace ligsim::study {

namespace fs = std::filesystem;

namespace {

/// One ligament's build figures from summary.json's stages called `prefix` + stage.
void built_ligament(const nlohmann::json& stages, const std::string& prefix, BuiltLigament& built)
{
  for (const auto& [name, stage] : stages.items()) {
    if (name.compare(0, prefix.size(), prefix) != 0)
      continue;
    const bool ran = stage.value("status", "") == "ran";
    built.build_s += ran ? stage.value("wall_s", 0.0) : stage.value("previous_wall_s", 0.0);
    built.peak_rss_mib =
        std::max(built.peak_rss_mib, ran ? stage.value("peak_rss_mib", 0.0)
                                         : stage.value("previous_peak_rss_mib", 0.0));
    if (name == prefix + "tetmesh") {
      const nlohmann::json& figures = stage["figures"];
      built.tets = figures.value("tets", 0);
      built.nodes = figures.value("nodes", 0);
    }
  }
}

/// One ligament's sweep against `motion`, with its own settings (ligament_settings).
FlexionFigures sweep_ligament(const sim::LigamentModel& ligament, const sim::KneeMotion& motion,
                              const sim::FlexionSettings& settings, const StageMeter& meter)
{
  FlexionFigures figures;
  figures.ligament = ligament.name;
  const auto start = std::chrono::steady_clock::now();
  const sim::KneeModel& model = ligament.model;
  const sim::HyperelasticBody body =
      sim::ligament_body(model, settings.material, settings.in_situ_strain);
  const sim::BoundaryConditions conditions =
      sim::knee_conditions(model, sim::femur_rigid_motion(motion));
  const sim::SweepSteps steps = sim::motion_steps(motion);
  figures.setup_s = seconds_since(start);
  figures.tets = static_cast<int>(body.element_count());

  std::vector<double> volumes(static_cast<std::size_t>(body.element_count()));
  for (Eigen::Index e = 0; e < body.element_count(); ++e)
    volumes[static_cast<std::size_t>(e)] = body.element_volume(e);
  double measuring_s = 0.0;
  const sim::SweepResult sweep = sim::run_flexion_sweep(
      body, conditions, settings,
      [&](const sim::AngleResult& angle, const sim::HyperelasticBody& swept,
          const Eigen::VectorXd& x) {
        const auto measuring = std::chrono::steady_clock::now();
        std::vector<double> stretch(volumes.size());
        for (Eigen::Index e = 0; e < swept.element_count(); ++e)
          stretch[static_cast<std::size_t>(e)] = swept.measures(x, e).fiber_stretch;
        AngleFigures row;
        row.angle_deg = angle.angle_deg;
        row.strain_energy_mj = angle.strain_energy_mj;
        row.mean_fiber_stretch = angle.mean_fiber_stretch;
        row.max_fiber_stretch = angle.max_fiber_stretch;
        row.regional_fiber_stretch = angle.max_regional_fiber_stretch;
        row.p95_fiber_stretch = weighted_quantile(stretch, volumes, 0.95);
        row.femur_force_n = angle.femur_force_n;
        figures.angles.push_back(row);
        measuring_s += seconds_since(measuring);
      },
      nullptr, &steps);
  figures.success = sweep.success;
  figures.failure = sweep.failure;
  figures.solve_s = sweep.wall_s - measuring_s;
  figures.peak_rss_mib = meter.peak_rss_mib();
  if (settings.mode == sim::FlexionMode::interactive) {
    figures.frames = sweep.frames;
    figures.frames_per_second = sweep.frames_per_second;
    figures.time_step_s = sweep.time_step_s;
  } else {
    figures.frames = static_cast<int>(sweep.angles.size());
  }
  return figures;
}

} // namespace

BuiltModel build_model(const StudyModel& model, const fs::path& dir)
{
  RunSummary summary("build");
  BuiltModel built;
  built.dir = dir;
  built.ligaments.resize(model.config.ligaments.size());
  if (model.knee) {
    summary.inputs() = {{"config", model.config.file.string()}, {"knee", true}};
    summary.parameters() = pipeline::to_json(model.config);
    ensure_directory(dir);
    // Ligament by ligament: one that cannot be built (a variant's surface that intersects
    // itself) fails alone, and the knee keeps the others.
    const pipeline::KneeConfig knee = pipeline::with_knee_anatomy(model.config);
    pipeline::KneeConfig built_ones = knee;
    built_ones.ligaments.clear();
    for (std::size_t l = 0; l < knee.ligaments.size(); ++l) {
      const pipeline::LigamentConfig& ligament = knee.ligaments[l];
      try {
        pipeline::build_knee_ligament(knee, ligament, dir, "model", false, summary);
        built_ones.ligaments.push_back(ligament);
      } catch (const Error& e) {
        built.ligaments[l].failure = e.what();
        summary.results()["failed"][ligament.name] = e.what();
      }
    }
    if (!built_ones.ligaments.empty()) {
      pipeline::write_knee_files(built_ones, dir);
    } else { // nothing to sweep, not even an earlier run's knee
      std::error_code ignored;
      fs::remove(dir / knee_manifest_file, ignored);
    }
  } else {
    const pipeline::BuildConfig& config = model.config.ligaments.front().build;
    summary.inputs() = {{"surface", config.surface.string()},
                        {"femur", config.femur.string()},
                        {"tibia", config.tibia.string()}};
    summary.parameters() = pipeline::to_json(config);
    pipeline::run_target(config, dir, "model", false, summary);
  }
  summary.write(dir);
  for (std::size_t l = 0; l < model.config.ligaments.size(); ++l)
    built_ligament(summary.json()["stages"], model.knee ? model.config.ligaments[l].name + "/" : "",
                   built.ligaments[l]);
  return built;
}

bool BuiltModel::any_built() const
{
  return std::any_of(ligaments.begin(), ligaments.end(),
                     [](const BuiltLigament& l) { return l.failure.empty(); });
}

const FlexionFigures* figures_of(const std::vector<FlexionFigures>& figures,
                                 const std::string& name)
{
  for (const FlexionFigures& f : figures)
    if (f.ligament == name)
      return &f;
  return nullptr;
}

double weighted_quantile(const std::vector<double>& values, const std::vector<double>& volumes,
                         double fraction)
{
  std::vector<std::size_t> order(values.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
  const double total = std::accumulate(volumes.begin(), volumes.end(), 0.0);
  double below = 0.0;
  for (std::size_t i : order) {
    below += volumes[i];
    if (below >= fraction * total)
      return values[i];
  }
  return order.empty() ? 0.0 : values[order.back()];
}

std::vector<FlexionFigures> run_flexion(const sim::FlexionSettings& settings)
{
  const StageMeter meter;
  std::vector<sim::LigamentModel> all = sim::load_knee(settings.model_dir, settings.ligament.name);
  // A [ligament] table for a ligament this knee lacks (left out of the study, or not built in
  // this variant) applies to none of its ligaments.
  sim::FlexionSettings own = settings;
  const bool knee = all.size() > 1 || all.front().manifest;
  if (knee && std::none_of(all.begin(), all.end(), [&](const sim::LigamentModel& l) {
        return l.name == settings.ligament.name;
      }))
    for (const char* key : {"ligament.name", "ligament.failure_strain", "ligament.failure_load_n"})
      own.given.erase(key);
  std::vector<sim::LigamentModel> ligaments = sim::chosen_ligaments(std::move(all), own);
  if (own.mode == sim::FlexionMode::interactive)
    sim::linear_tets_for_frames(ligaments);
  // The ligaments share the bones and the anatomy: the motion comes from any of them.
  const sim::KneeMotion motion = sim::resolve_knee_motion(ligaments.front().model, own);
  const double shared_setup_s = meter.wall_s();
  std::vector<FlexionFigures> figures;
  for (const sim::LigamentModel& ligament : ligaments) {
    figures.push_back(
        sweep_ligament(ligament, motion, sim::ligament_settings(own, ligament), meter));
    figures.back().setup_s += shared_setup_s;
  }
  return figures;
}

} // namespace ligsim::study
