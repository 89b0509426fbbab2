#include "pipeline/commands/commands.hpp"

#include "common/error.hpp"
#include "common/progress.hpp"
#include "pipeline/commands/flexion_options.hpp"
#include "pipeline/view/live_window.hpp"
#include "pipeline/view/membrane_window.hpp"
#include "pipeline/view/view_script.hpp"
#include "sim/flexion/free_flexion.hpp"
#include "sim/flexion/knee_motion.hpp"
#include "sim/flexion/knee_sweep.hpp"
#include "sim/flexion/live_knee.hpp"
#include "sim/membrane/scene/scene.hpp"
#include "sim/membrane/scene/tear_simulation.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <memory>

namespace ligsim::cli {

namespace {

struct ViewOptions {
  std::filesystem::path scene; ///< a tearing scene, instead of a model
  FlexionOptions flexion;
  std::filesystem::path script;
  std::filesystem::path record;
  double max_angle_deg = 0.0; ///< 0: the config's last angle
  int width = 1024;
};

/// A tearing scene torn live by its own pull and the hand's.
void view_membrane(const ViewOptions& options)
{
  if (!options.flexion.model.empty())
    fail("view: --model is for a knee model, not a tearing scene");
  membrane::TearSimulation simulation(membrane::load_scene(options.scene));
  MembraneWindowOptions window;
  window.record = options.record;
  window.width = options.width;
  window.interactive = options.record.empty() && options.script.empty();
  if (!options.script.empty())
    window.hand = ViewScript::read(options.script, {"x_mm", "y_mm"});
  play_membrane(simulation, window);
}

void run_view(const ViewOptions& options)
{
  require_display();
  if (!options.scene.empty()) {
    view_membrane(options);
    return;
  }
  if (options.flexion.model.empty())
    fail("view: give a built model (--model DIR) or a tearing scene (a .toml file)");
  sim::FlexionSettings settings = flexion_settings_from(options.flexion, "view");
  const double max_angle =
      options.max_angle_deg > 0.0 ? options.max_angle_deg : settings.angles_deg.back();
  const std::vector<sim::LigamentModel> whole =
      sim::load_knee(settings.model_dir, settings.ligament.name);
  std::vector<sim::LigamentModel> ligaments = sim::chosen_ligaments(whole, settings);
  const std::string element_note = sim::linear_tets_for_frames(ligaments);
  if (!element_note.empty())
    log_info(element_note);
  const bool free_path = sim::choose_free_path(settings, whole);
  settings.angles_deg = {0.0, max_angle};
  sim::KneeMotion motion = sim::resolve_knee_motion(ligaments.front().model, settings);
  if (free_path) {
    // The knee's own path, found first every 10 degrees; the view then moves along it.
    std::vector<double> angles;
    for (double angle = 0.0; angle < max_angle; angle += 10.0)
      angles.push_back(angle);
    angles.push_back(max_angle);
    motion.angles_deg = angles;
    log_info(fmt::format("view: finding the knee's own path at {} angles first (the femur free "
                         "in five coordinates)",
                         angles.size()));
    const sim::FreeFlexion free =
        sim::find_free_flexion(sim::free_path_ligaments(whole, settings), motion, settings,
                               settings.model_dir / "contact");
    if (!free.found.success)
      fail<SolverError>("view: the knee's own path: {}", free.found.failure);
    motion = free.motion;
  }
  log_info(fmt::format("view: settling {} ligament{} at 0 deg", ligaments.size(),
                       ligaments.size() > 1 ? "s" : ""));
  sim::LiveKnee knee(ligaments, motion, settings, settings.model_dir / "contact", max_angle);
  LiveWindowOptions window_options;
  window_options.record = options.record;
  window_options.width = options.width;
  window_options.height = options.width * 3 / 4;
  LiveWindow window(knee, ligaments.front().model, motion.axis.axis.direction, window_options);
  if (!options.script.empty()) {
    const int frames = window.run_script(ViewScript::read(options.script));
    log_info(
        fmt::format("view: {} frames played{}", frames,
                    options.record.empty() ? "" : " and recorded in " + options.record.string()));
    return;
  }
  log_info("view: the slider or the arrow keys move the femur; r resets, c toggles contact, s "
           "takes a screenshot, q quits");
  window.run_interactive();
}

} // namespace

void add_view_command(CLI::App& app)
{
  auto options = std::make_shared<ViewOptions>();
  auto* command = app.add_subcommand(
      "view", "move a built knee by hand in a live window: the femur follows a slider, the "
              "ligaments answer frame by frame");
  command
      ->add_option("scene", options->scene,
                   "a tearing scene (.toml, data/scenes/square-sheet-45.toml) to tear live, "
                   "instead of a model")
      ->check(CLI::ExistingFile);
  add_flexion_options(*command, options->flexion, true);
  command
      ->add_option("--script", options->script,
                   "play an interaction: a CSV with columns time_s,angle_deg (a knee's slider "
                   "over simulated time) or time_s,x_mm,y_mm (a hand pulling a tearing scene's "
                   "sheet); every frame is drawn")
      ->check(CLI::ExistingFile);
  command->add_option(
      "--record", options->record,
      "write every drawn frame as frame_NNNNN.png, a frames.csv and a frames.pvd here");
  command->add_option("--max-angle", options->max_angle_deg,
                      "the slider's largest angle, deg (default: the config's last angle)");
  command->add_option("--size", options->width, "the window's width, pixels (height 3/4 of it)")
      ->check(CLI::Range(200, 4096));
  command->callback([options] { run_view(*options); });
}

} // namespace ligsim::cli
