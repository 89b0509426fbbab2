#include "pipeline/study/study_runs.hpp"

#include "common/progress.hpp"
#include "common/resources.hpp"
#include "common/run_summary.hpp"
#include "pipeline/stage_graph/stage_graph.hpp"
#include "sim/flexion/knee_flexion.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <numeric>

namespace ligsim::study {

namespace fs = std::filesystem;

BuiltModel build_model(const pipeline::BuildConfig& config, const fs::path& dir)
{
  RunSummary summary("build");
  summary.inputs() = {{"surface", config.surface.string()},
                      {"femur", config.femur.string()},
                      {"tibia", config.tibia.string()}};
  summary.parameters() = pipeline::to_json(config);
  pipeline::run_target(config, dir, "model", false, summary);
  summary.write(dir);

  BuiltModel built;
  built.dir = dir;
  built.reused = true;
  for (const auto& [name, stage] : summary.json()["stages"].items()) {
    const bool ran = stage.value("status", "") == "ran";
    built.reused = built.reused && !ran;
    built.build_s += ran ? stage.value("wall_s", 0.0) : stage.value("previous_wall_s", 0.0);
    built.peak_rss_mib =
        std::max(built.peak_rss_mib, ran ? stage.value("peak_rss_mib", 0.0)
                                         : stage.value("previous_peak_rss_mib", 0.0));
    if (name == "tetmesh") {
      const nlohmann::json& figures = stage["figures"];
      built.tets = figures.value("tets", 0);
      built.nodes = figures.value("nodes", 0);
    }
  }
  return built;
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

FlexionFigures run_flexion(const sim::FlexionSettings& settings)
{
  FlexionFigures figures;
  const StageMeter meter;
  const sim::KneeModel model = sim::load_knee_model(settings.model_dir);
  const sim::KneeMotion motion = sim::resolve_knee_motion(model, settings);
  const sim::HyperelasticBody body(model.mesh, settings.material,
                                   sim::prestretched_fibers(model, settings.in_situ_strain));
  const sim::BoundaryConditions conditions =
      sim::knee_conditions(model, sim::femur_rigid_motion(motion));
  const sim::SweepSteps steps = sim::motion_steps(motion);
  figures.setup_s = meter.wall_s();
  figures.tets = static_cast<int>(body.element_count());

  std::vector<double> volumes(static_cast<std::size_t>(body.element_count()));
  for (Eigen::Index e = 0; e < body.element_count(); ++e)
    volumes[static_cast<std::size_t>(e)] = body.shape(e).V0;
  double measuring_s = 0.0;
  const sim::SweepResult sweep = sim::run_flexion_sweep(
      body, conditions, settings,
      [&](const sim::AngleResult& angle, const Eigen::VectorXd& x) {
        const auto start = std::chrono::steady_clock::now();
        std::vector<double> stretch(volumes.size());
        for (Eigen::Index e = 0; e < body.element_count(); ++e)
          stretch[static_cast<std::size_t>(e)] = body.measures(x, e).fiber_stretch;
        AngleFigures row;
        row.angle_deg = angle.angle_deg;
        row.strain_energy_mj = angle.strain_energy_mj;
        row.mean_fiber_stretch = angle.mean_fiber_stretch;
        row.max_fiber_stretch = angle.max_fiber_stretch;
        row.p95_fiber_stretch = weighted_quantile(stretch, volumes, 0.95);
        row.femur_force_n = angle.femur_force_n;
        figures.angles.push_back(row);
        measuring_s += seconds_since(start);
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

} // namespace ligsim::study
