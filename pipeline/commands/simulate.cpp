#include "pipeline/commands/commands.hpp"
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
  parameters["kind"] = scene.kind == sim::SceneKind::quasi_static ? "static" : "dynamic";
  parameters["mu_mpa"] = scene.material.mu_mpa;
  parameters["k_mpa"] = scene.material.bulk_modulus_mpa;
  parameters["volumetric"] = to_string(scene.material.volumetric);
  if (scene.material.fiber) {
    const sim::FiberParameters& fiber = *scene.material.fiber;
    parameters["fiber"] = {{"c3_mpa", fiber.c3_mpa},
                           {"c4", fiber.c4},
                           {"c5_mpa", fiber.c5_mpa},
                           {"lambda_star", fiber.lambda_star},
                           {"convention", to_string(fiber.convention)}};
  }
  if (scene.kind == sim::SceneKind::quasi_static) {
    parameters["load_steps"] = scene.newton.load_steps;
    parameters["residual_tolerance"] = scene.newton.residual_tolerance;
    parameters["linear_solver"] = to_string(scene.newton.linear_solver);
  } else {
    parameters["time_step_s"] = scene.dynamics.time_step_s;
    parameters["frames"] = scene.dynamics.frames;
    parameters["until_converged"] = scene.dynamics.until_converged;
    parameters["linear_solver"] = to_string(scene.dynamics.linear_solver);
  }
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
