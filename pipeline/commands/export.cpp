#include "pipeline/commands/commands.hpp"
#include "pipeline/commands/flexion_options.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "sim/febio/feb_writer.hpp"
#include "sim/febio/knee_feb.hpp"
#include "sim/flexion/knee_flexion.hpp"
#include "sim/flexion/knee_sweep.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace ligsim::cli {

namespace fs = std::filesystem;

namespace {

struct ExportOptions {
  FlexionOptions flexion;
  fs::path out;
  sim::FebContactSettings contact;
};

void run_export_febio(const ExportOptions& options)
{
  if (options.out.extension() != ".feb")
    fail("export febio: --out {}: give a file name ending in .feb", options.out.string());
  sim::FlexionSettings settings = flexion_settings_from(options.flexion, "export febio");
  const sim::KneeModel model = sim::load_ligament_as_flexed(settings, "export febio");
  const sim::KneeMotion motion = sim::resolve_knee_motion(model, settings);
  const sim::BoundaryConditions conditions =
      sim::knee_conditions(model, sim::femur_rigid_motion(motion));
  const sim::SweepSteps steps = sim::motion_steps(motion);
  std::vector<std::string> warnings;
  sim::OverlapReport report;
  const sim::KneeModel exported = sim::feb_start_model(model, settings, conditions, &report);
  if (report.reshaped)
    log_info(fmt::format("export febio: the ligament's rest shape is pushed out of the bones "
                         "([contact] initial_overlap = \"reshape\"): nodes moved by up to "
                         "{:.3g} mm",
                         report.max_node_move_mm));
  const sim::FebProblem problem = sim::knee_feb_problem(
      exported, settings, conditions, steps, motion.axis.axis.point_mm, warnings, options.contact);
  for (const std::string& warning : warnings)
    log_info("warning: " + warning);
  if (options.out.has_parent_path())
    ensure_directory(options.out.parent_path());
  sim::write_feb(options.out, problem);
  log_info(fmt::format("wrote {}: {} nodes, {} tets, {} steps ({} deg), contact {}; run it with "
                       "`febio4 -i {}`",
                       options.out.string(), model.mesh.V.rows(), model.mesh.T.rows(),
                       steps.angles_deg.size(), steps.angles_deg.back(),
                       problem.contact ? "on" : "off", options.out.filename().string()));
}

} // namespace

void add_export_command(CLI::App& app)
{
  auto* command = app.add_subcommand("export", "a built knee model as another program's input");
  command->require_subcommand(1);
  auto options = std::make_shared<ExportOptions>();
  auto* febio = command->add_subcommand(
      "febio", "the flexion sweep as a FEBio 4 input (.feb): the same mesh, fibers, material, "
               "in-situ strain, femur motion and contact as `ligsim flexion`");
  add_flexion_options(*febio, options->flexion, false);
  febio->add_option("--out", options->out, "the .feb file to write")->required();
  febio
      ->add_option("--febio-penalty", options->contact.penalty,
                   "contact on: scale of FEBio's automatic contact penalty")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  febio->callback([options] { run_export_febio(*options); });
}

} // namespace ligsim::cli
