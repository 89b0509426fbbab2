#include "pipeline/commands/commands.hpp"

#include "common/error.hpp"
#include "common/progress.hpp"
#include "pipeline/stage_graph/build_config.hpp"
#include "pipeline/stage_graph/knee_config.hpp"
#include "pipeline/stage_graph/stage_graph.hpp"
#include "sim/flexion/flexion_config.hpp"
#include "sim/membrane/scene/scene.hpp"
#include "sim/scene/scene.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <filesystem>
#include <set>
#include <string>
#include <vector>

namespace ligsim::cli {

namespace fs = std::filesystem;

namespace {

/// The value of `name` when it was given on the command line, else "".
std::string given(const CLI::App& command, const std::string& name)
{
  const CLI::Option* option = command.get_option_no_throw(name);
  if (option == nullptr || option->count() == 0)
    return "";
  return option->as<std::string>();
}

/// A surface or label map a build config names must exist (a glTF file's "#mesh" aside).
void check_input_file(const fs::path& file, const std::string& config)
{
  if (file.empty())
    return;
  const std::string text = file.string();
  const fs::path on_disk = text.substr(0, text.find('#'));
  if (!fs::is_regular_file(on_disk))
    fail("{}: the file '{}' it names does not exist", config, on_disk.string());
}

void check_inputs(const pipeline::BuildConfig& config, const std::string& file)
{
  for (const fs::path* input :
       {&config.surface, &config.femur, &config.tibia, &config.labels, &config.colour_table})
    check_input_file(*input, file);
}

/// One ligament's config, or a knee's (every ligament's inputs and the fibula).
void check_build_config(const std::string& file)
{
  if (!pipeline::is_knee_config(file)) {
    check_inputs(pipeline::load_build_config(file), file);
    return;
  }
  const pipeline::KneeConfig knee = pipeline::load_knee_config(file);
  for (const fs::path* input : {&knee.fibula, &knee.labels, &knee.colour_table})
    check_input_file(*input, file);
  for (const pipeline::LigamentConfig& ligament : knee.ligaments)
    check_inputs(ligament.build, file);
}

/// Loads every config and scene file the command names, with the reader the job would use.
void check_files(const CLI::App& command, const std::string& path,
                 const std::set<std::string>& build_commands)
{
  if (const std::string file = given(command, "--model-config"); !file.empty())
    check_build_config(file);
  if (const std::string file = given(command, "--config"); !file.empty()) {
    if (build_commands.count(path) != 0) {
      check_build_config(file);
    } else {
      sim::FlexionSettings settings;
      sim::read_flexion_config(file, settings);
    }
  }
  if (const std::string file = given(command, "scene"); !file.empty()) {
    if (path == "tear" || path == "view") // view's scene is a tearing scene
      membrane::load_scene(file);
    else
      sim::load_scene(file);
  }
  log_info(fmt::format("check only: {}: the command line and the files it names are valid", path));
}

/// CLI11 reports arguments nobody took only after the callbacks; the check does it first.
void reject_extras(const CLI::App& command)
{
  const CLI::App* root = &command;
  while (root->get_parent() != nullptr)
    root = root->get_parent();
  const std::vector<std::string> extras = root->remaining(true);
  if (!extras.empty())
    throw CLI::ExtrasError(extras);
}

/// Every job (a subcommand without subcommands of its own) checks as soon as its arguments are
/// parsed, then stops the parse with CLI11's Success, so that the job's callback never runs. (The
/// callback stays in place: it owns the job's option values.)
void add_checks(CLI::App& command, const std::string& path,
                const std::set<std::string>& build_commands)
{
  for (CLI::App* sub : command.get_subcommands({})) {
    const std::string sub_path = path.empty() ? sub->get_name() : path + " " + sub->get_name();
    if (!sub->get_subcommands({}).empty()) {
      add_checks(*sub, sub_path, build_commands);
      continue;
    }
    sub->parse_complete_callback([sub, sub_path, build_commands] {
      reject_extras(*sub);
      check_files(*sub, sub_path, build_commands);
      throw CLI::Success();
    });
  }
}

} // namespace

void make_jobs_check_only(CLI::App& app)
{
  std::set<std::string> build_commands = {"build"};
  for (const pipeline::Stage& stage : pipeline::build_stages())
    build_commands.insert(stage.name);
  add_checks(app, "", build_commands);
}

} // namespace ligsim::cli
