#include "pipeline/commands/commands.hpp"
#include "pipeline/reports/config_json.hpp"
#include "pipeline/scenes/scene_runner.hpp"

#include "common/error.hpp"
#include "common/progress.hpp"
#include "common/run_summary.hpp"
#include "common/toml_overrides.hpp"
#include "sim/scene/scene.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace ligsim::cli {

namespace fs = std::filesystem;

namespace {

struct SimulateOptions {
  fs::path scene;
  fs::path out;
  std::vector<std::string> set; ///< --set TABLE.KEY=VALUE over the scene
};

void run_simulate(const SimulateOptions& options)
{
  RunSummary summary("simulate");
  summary.inputs()["scene"] = options.scene.string();
  if (!options.set.empty())
    summary.inputs()["set"] = options.set;
  const sim::Scene scene = sim::load_scene(options.scene, options.set);
  summary.inputs()["mesh"] = scene.mesh_source;
  nlohmann::json& parameters = summary.parameters();
  parameters["config"] = reports::to_json(scene);
  nlohmann::json sets = nlohmann::json::object();
  for (const auto& [name, nodes] : scene.node_sets)
    sets[name] = nodes.size();
  parameters["node_sets"] = sets;

  const scenes::SceneRunReport report = scenes::run_scene(scene, options.out, summary);
  summary.write(options.out);
  if (!report.success)
    fail<SolverError>("{}: {} (outputs up to the last good state are in {})",
                      options.scene.string(), report.failure, options.out.string());
  log_info(fmt::format("wrote {}", (options.out / "summary.json").string()));
}

} // namespace

void add_simulate_command(CLI::App& app)
{
  auto options = std::make_shared<SimulateOptions>();
  auto* command = app.add_subcommand(
      "simulate", "run a hyperelastic scene file (VTU per step, series.pvd, summary.json)");
  command->add_option("scene", options->scene, "scene file (.toml)")->required();
  command->add_option("--out", options->out, "output folder")->required();
  command->add_option("--set", options->set, kSetHelp)
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  command->callback([options] { run_simulate(*options); });
}

} // namespace ligsim::cli
