#include "pipeline/commands/commands.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "common/pvd_file.hpp"
#include "common/resources.hpp"
#include "common/run_summary.hpp"
#include "common/toml_overrides.hpp"
#include "common/vtk_files.hpp"
#include "pipeline/render/membrane_frame.hpp"
#include "pipeline/render/tear_frame_picture.hpp"
#include "pipeline/reports/config_json.hpp"
#include "sim/membrane/output/tear_path.hpp"
#include "sim/membrane/scene/scene.hpp"
#include "sim/membrane/scene/tear_metrics.hpp"
#include "sim/membrane/scene/tear_simulation.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

namespace ligsim::cli {

namespace fs = std::filesystem;
using namespace ligsim::membrane;

namespace {

struct TearOptions {
  fs::path scene;
  fs::path out;
  int max_steps = 0;   ///< 0: the scene's
  int frame_every = 0; ///< 0: the scene's
  int max_frames = 1000;
  bool no_png = false;
  int png_size = 800;
  std::vector<std::string> set; ///< --set TABLE.KEY=VALUE over the scene
};

double median(std::vector<double> values)
{
  if (values.empty())
    return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t middle = values.size() / 2;
  return values.size() % 2 ? values[middle] : 0.5 * (values[middle - 1] + values[middle]);
}

/// Writes frame `index` (VTU, and PNG unless disabled); returns the VTU's name.
std::string write_frame(const TearSimulation& simulation, const TearOptions& options,
                        const render::FrameView& view, int index)
{
  const std::vector<double> criterion =
      simulation.tearing().element_criterion(simulation.mesh(), simulation.elements());
  const std::string name = fmt::format("frame_{:05d}", index);
  write_vtk(render::membrane_frame(simulation, criterion), options.out / (name + ".vtu"));
  if (!options.no_png)
    render::render_frame(simulation, criterion, view).write_png(options.out / (name + ".png"));
  return name + ".vtu";
}

nlohmann::json results_of(const TearSimulation& simulation)
{
  const TearMetrics& metrics = simulation.metrics();
  std::vector<TearEvent> events;
  for (const RecordedEvent& recorded : metrics.events)
    events.push_back(recorded.event);
  nlohmann::json results;
  results["steps"] = metrics.steps;
  results["simulated_time_s"] = simulation.time_s();
  results["ms_per_step"] = median(metrics.step_ms);
  results["ms_per_step_max"] =
      metrics.step_ms.empty() ? 0.0
                              : *std::max_element(metrics.step_ms.begin(), metrics.step_ms.end());
  results["cg_iterations_mean"] =
      metrics.cg_iterations.empty()
          ? 0.0
          : std::accumulate(metrics.cg_iterations.begin(), metrics.cg_iterations.end(), 0.0) /
                metrics.cg_iterations.size();
  results["propagation_events"] = metrics.propagation_events;
  results["initiations"] = metrics.initiations;
  results["face_splits"] = metrics.face_splits;
  results["initial_elements"] = metrics.initial_elements;
  results["elements"] = simulation.mesh().triangle_count();
  results["nodes"] = simulation.mesh().node_count();
  results["min_angle_deg"] = metrics.min_angle_rad * 180.0 / M_PI;
  const double direction = mean_tear_direction_deg(events);
  results["tear_direction_deg"] =
      std::isfinite(direction) ? nlohmann::json(direction) : nlohmann::json();
  results["separated"] = metrics.separated;
  if (metrics.onset) {
    results["onset_step"] = metrics.onset->step;
    results["onset_load_n"] = metrics.onset->load_n;
  }
  if (const auto& centre = simulation.scene().run.centre_mm) {
    const RadiusStatistics radius = tear_radius(events, *centre);
    results["tear_radius_mean_mm"] = radius.mean_mm;
    results["tear_radius_cv"] = radius.coefficient_of_variation;
    results["turned_deg"] = metrics.turned_rad * 180.0 / M_PI;
  }
  return results;
}

void run_tear(const TearOptions& options)
{
  Scene scene = load_scene(options.scene, options.set);
  if (options.max_steps > 0)
    scene.run.max_steps = options.max_steps;
  if (options.frame_every > 0)
    scene.run.frame_every = options.frame_every;

  RunSummary summary("tear");
  summary.inputs()["scene"] = options.scene.string();
  if (!options.set.empty())
    summary.inputs()["set"] = options.set;
  nlohmann::json& parameters = summary.parameters();
  parameters["name"] = scene.name;
  parameters["config"] = reports::to_json(scene);
  parameters["png"] = !options.no_png;

  StageMeter setup_meter;
  TearSimulation simulation(scene);
  summary.add_stage("setup", setup_meter, {{"elements", simulation.mesh().triangle_count()}});

  ensure_directory(options.out);
  const render::FrameView view = render::frame_view(simulation.mesh(), options.png_size);
  std::vector<std::pair<double, std::string>> frames;
  StageMeter run_meter;
  double output_s = 0.0;
  const auto frame = [&] {
    if (static_cast<int>(frames.size()) >= options.max_frames)
      return;
    const StageMeter frame_meter;
    frames.emplace_back(simulation.time_s(),
                        write_frame(simulation, options, view, static_cast<int>(frames.size())));
    output_s += frame_meter.wall_s();
  };
  frame();
  Progress progress("tear", static_cast<std::size_t>(scene.run.max_steps));
  while (!simulation.finished()) {
    simulation.step();
    progress.advance();
    const bool last = simulation.finished();
    if (simulation.metrics().steps % scene.run.frame_every == 0 || last) {
      if (last && static_cast<int>(frames.size()) >= options.max_frames)
        frames.pop_back(); // the final state replaces the last frame within the cap
      frame();
    }
  }
  progress.finish();
  write_pvd(options.out / "frames.pvd", frames);
  write_text_atomically(options.out / "tear_path.csv", tear_path_csv(simulation.metrics()));

  nlohmann::json& stage = summary.add_stage("simulate", run_meter, {{"frames", frames.size()}});
  stage["output_wall_s"] = output_s;
  summary.results() = results_of(simulation);
  summary.write(options.out);
  const nlohmann::json& results = summary.results();
  log_info(fmt::format("{}: {} steps, {:.3f} ms per step, {} propagation events, {} elements; "
                       "wrote {}",
                       scene.name, results["steps"].get<int>(),
                       results["ms_per_step"].get<double>(),
                       results["propagation_events"].get<int>(), results["elements"].get<int>(),
                       (options.out / "summary.json").string()));
}

} // namespace

void add_tear_command(CLI::App& app)
{
  auto options = std::make_shared<TearOptions>();
  auto* command = app.add_subcommand(
      "tear", "tear a fibrous membrane scene (VTU and PNG frames, frames.pvd, summary.json)");
  command
      ->add_option("scene", options->scene,
                   "scene file (.toml), e.g. data/scenes/square-sheet-45.toml")
      ->required();
  command->add_option("--out", options->out, "output folder")->required();
  command->add_option("--set", options->set, kSetHelp)
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  command
      ->add_option("--max-steps", options->max_steps,
                   "stop after this many steps (default: the scene's)")
      ->check(CLI::PositiveNumber);
  command
      ->add_option("--frame-every", options->frame_every,
                   "steps between frames (default: the scene's)")
      ->check(CLI::PositiveNumber);
  command->add_option("--max-frames", options->max_frames, "write at most this many frames")
      ->check(CLI::PositiveNumber);
  command->add_option("--png-size", options->png_size, "larger side of the PNG frames, pixels")
      ->check(CLI::Range(16, 8192));
  command->add_flag("--no-png", options->no_png, "write no PNG frames");
  command->callback([options] { run_tear(*options); });
}

} // namespace ligsim::cli
