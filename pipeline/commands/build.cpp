#include "pipeline/commands/commands.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/knee_anatomy.hpp"
#include "common/progress.hpp"
#include "common/resources.hpp"
#include "common/run_summary.hpp"
#include "common/toml_overrides.hpp"
#include "common/vtk_files.hpp"
#include "pipeline/commands/anatomy_outputs.hpp"
#include "pipeline/commands/key_flags.hpp"
#include "pipeline/reports/knee_reports.hpp"
#include "pipeline/stage_graph/build_config.hpp"
#include "pipeline/stage_graph/companion_build.hpp"
#include "pipeline/stage_graph/knee_build.hpp"
#include "pipeline/stage_graph/knee_from_labels.hpp"
#include "pipeline/stage_graph/label_inputs.hpp"
#include "pipeline/stage_graph/stage_files.hpp"
#include "pipeline/stage_graph/stage_graph.hpp"
#include "sim/flexion/plausibility.hpp"
#include "stages/io/vtk_convert.hpp"

#include <CLI/CLI.hpp>
#include <vtkPolyData.h>

#include <memory>

namespace ligsim::cli {

namespace fs = std::filesystem;
using pipeline::BuildConfig;

namespace {

/// Command-line flags of `build` and of every stage subcommand; each overrides the config file.
struct BuildOptions {
  std::string config, surface, femur, tibia, out;
  std::vector<std::string> set; ///< --set TABLE.KEY=VALUE over the config
  std::string labels, colour_table, ligament_label, femur_label, tibia_label;
  KeyFlags key_flags; ///< the stage and attachment flags: short names for config keys
  bool force = false, no_images = false;
};

void add_options(CLI::App* command, BuildOptions& o)
{
  command
      ->add_option("--config", o.config,
                   "TOML file with every parameter (docs/build.md); flags override it")
      ->check(CLI::ExistingFile);
  command->add_option("--set", o.set, kSetHelp)
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  command->add_option("--surface", o.surface,
                      "ligament surface: .stl, .obj, .ply, .vtp or .vtk (mm), or .glb/.gltf "
                      "(metres) with #MESH to choose one of several meshes");
  command->add_option("--femur", o.femur, "femur surface (optional)");
  command->add_option("--tibia", o.tibia, "tibia surface (optional)");
  command->add_option("--out", o.out, "output folder")->required();
  auto* label_map = "Segmentation label map (instead of surfaces)";
  command
      ->add_option("--labels", o.labels,
                   "label map: .nrrd, .seg.nrrd, .nii, .nii.gz, .mha or .mhd (physical LPS frame)")
      ->group(label_map);
  command
      ->add_option("--ligament-label", o.ligament_label,
                   "the ligament's label: a number or a name (segment name or colour table)")
      ->group(label_map);
  command->add_option("--femur-label", o.femur_label, "the femur's label (optional)")
      ->group(label_map);
  command->add_option("--tibia-label", o.tibia_label, "the tibia's label (optional)")
      ->group(label_map);
  command
      ->add_option("--colour-table", o.colour_table,
                   "label names: value name r g b a lines (default: a .ctbl or .txt beside the "
                   "label map, same stem)")
      ->group(label_map);
  auto* attach = "Attachment areas";
  auto& keys = o.key_flags;
  for (const char* bone : {"femur", "tibia"}) {
    const std::string table = fmt::format("attachments.{}.", bone);
    const char* area = bone == std::string("femur") ? "A1" : "A2";
    keys.add<std::string>(*command, fmt::format("--{}-rule", bone),
                          "auto, indices, array, proximity, patch, landmark or end",
                          {table + "rule"})
        ->group(attach);
    keys.add<std::vector<int>>(*command, fmt::format("--{}-indices", bone),
                               fmt::format("ligament vertex indices of {}", area),
                               {table + "indices"})
        ->delimiter(',')
        ->group(attach);
    keys.add<std::string>(*command, fmt::format("--{}-array", bone),
                          fmt::format("point-data array marking {}, non-zero", area),
                          {table + "array"})
        ->group(attach);
    keys.add<std::string>(*command, fmt::format("--{}-end", bone),
                          "end rule: proximal, distal, min, max or auto", {table + "end"})
        ->group(attach);
  }
  keys.add<double>(*command, "--attach-distance",
                   "proximity rule: max distance to the bone, mm, both areas (default 1)",
                   {"attachments.femur.distance_mm", "attachments.tibia.distance_mm"})
      ->group(attach);
  keys.add<double>(*command, "--end-length",
                   "end rule: length of the end along the main axis, mm, both areas (default 5)",
                   {"attachments.femur.end_length_mm", "attachments.tibia.end_length_mm"})
      ->group(attach);
  auto* stages = "Stage parameters";
  keys.add<double>(*command, "--voxel", "voxel spacing, mm (default: thickness / 8)",
                   {"voxelize.spacing_mm"})
      ->group(stages);
  keys.add<double>(*command, "--alpha", "centerline medial weight in [0, 1] (default 0.1)",
                   {"centerline.alpha"})
      ->group(stages);
  keys.add<std::string>(
          *command, "--span",
          "centerline between the areas' means (default) or through the whole attachments",
          {"centerline.span"})
      ->check(CLI::IsMember({"means", "attachments"}))
      ->group(stages);
  keys.add<std::string>(*command, "--field-method", "geometric (default) or laplace",
                        {"field.method"})
      ->group(stages);
  keys.add<double>(*command, "--cell-size", "tet mesh max circumradius, mm",
                   {"tetmesh.cell_size_mm"})
      ->group(stages);
  keys.add<double>(*command, "--facet-size", "tet mesh max surface Delaunay ball radius, mm",
                   {"tetmesh.facet_size_mm"})
      ->group(stages);
  keys.add<double>(*command, "--facet-distance", "tet mesh max distance to the surface, mm",
                   {"tetmesh.facet_distance_mm"})
      ->group(stages);
  keys.add<int>(*command, "--order", "tet order: 1 linear, 2 10-node (default: the config's)",
                {"tetmesh.order"})
      ->check(CLI::IsMember({1, 2}))
      ->group(stages);
  keys.add<double>(*command, "--radius-edge", "tet mesh radius-edge bound (default 2)",
                   {"tetmesh.radius_edge_ratio"})
      ->group(stages);
  keys.add<double>(*command, "--in-situ-strain", "fiber pre-strain (default 0.029)",
                   {"model.in_situ_strain"})
      ->group(stages);
  command->add_flag("--force", o.force, "rerun every stage, ignoring the cache");
  command->add_flag("--no-images", o.no_images,
                    "no anatomy.png (the landmarks on the bones; no X server needed)");
  keys.add_switch(*command, "--strict",
                  "refuse a defective ligament surface instead of repairing it", "input.strict");
}

void set_if(const std::string& value, std::string& target)
{
  if (!value.empty())
    target = value;
}

/// The --set assignments, then the stage and attachment flags as the config keys they set, under
/// `prefix` ("ligament." over every ligament of a knee): the flags win, and the config's reader
/// checks them as it checks the file.
std::vector<std::string> with_flag_assignments(const BuildOptions& o, const std::string& prefix)
{
  std::vector<std::string> set = o.set;
  for (std::string& assignment : o.key_flags.assignments(prefix))
    set.push_back(std::move(assignment));
  return set;
}

BuildConfig resolve_config(const BuildOptions& o)
{
  const std::vector<std::string> set = with_flag_assignments(o, "");
  BuildConfig config =
      o.config.empty() && set.empty() ? BuildConfig{} : pipeline::load_build_config(o.config, set);
  if (!o.surface.empty())
    config.surface = o.surface;
  if (!o.femur.empty())
    config.femur = o.femur;
  if (!o.tibia.empty())
    config.tibia = o.tibia;
  if (!o.labels.empty())
    config.labels = o.labels;
  if (!o.colour_table.empty())
    config.colour_table = o.colour_table;
  set_if(o.ligament_label, config.ligament_label);
  set_if(o.femur_label, config.femur_label);
  set_if(o.tibia_label, config.tibia_label);
  return config;
}

/// What the anatomy stage found, and what it could not, on stderr (anatomy.json has it all),
/// and the landmarks as points and in a picture.
void report_anatomy(const fs::path& dir, bool picture)
{
  if (!fs::exists(dir / knee_anatomy_file))
    return; // a stage that does not need it
  write_anatomy_outputs(dir, picture);
  const KneeAnatomy anatomy = read_knee_anatomy(dir);
  if (!anatomy.side.empty())
    log_info(fmt::format("anatomy: a {} knee ({})", anatomy.side, anatomy.side_source));
  std::vector<std::string> found;
  for (const auto& [name, landmark] : anatomy.landmarks)
    found.push_back(name);
  if (!found.empty())
    log_info(fmt::format("anatomy: landmarks {} ({})", fmt::join(found, ", "),
                         (dir / knee_anatomy_file).string()));
  for (const std::string& line : anatomy.not_found)
    log_info("anatomy: not found: " + line);
}

/// Each built ligament's mean cross-section beside the published one, with a warning on stderr
/// for one too thin to stand for the real ligament (sim::thin_ligament_finding).
nlohmann::json report_thin_ligaments(const pipeline::KneeConfig& knee, const fs::path& out)
{
  nlohmann::json json = nlohmann::json::object();
  for (const pipeline::LigamentConfig& ligament : knee.ligaments) {
    const fs::path dir = out / ligament.name;
    QuadraticTetrahedra tet10; // the corners are the volume's
    const auto thickness =
        sim::ligament_thickness(pipeline::load_mesh(dir / pipeline::files::model, &tet10),
                                io::points_of(read_vtp(dir / pipeline::files::centerline)));
    if (!thickness)
      continue;
    json[ligament.name] = reports::thickness_json(*thickness, ligament.name);
    if (const auto finding = sim::thin_ligament_finding(ligament.name, *thickness))
      log_info(fmt::format("warning: {}", *finding));
  }
  return json;
}

/// What the repairs of a build's surfaces did, as summary.json holds it.
struct InputRepairs {
  nlohmann::json bones = nlohmann::json::object();     ///< per bone given
  nlohmann::json ligaments = nlohmann::json::object(); ///< per ligament name ("" for one alone)
};

/// Reads and repairs every surface of a build before any stage runs, so that bad input leaves
/// nothing behind: the bones (name, file; no file, no bone) and the ligaments (name, build
/// config; "" for a one-ligament build), each ligament required to lie near a bone. Once all are
/// read, says each repair on stderr.
InputRepairs read_inputs(const std::vector<std::pair<std::string, fs::path>>& bone_files,
                         const std::vector<std::pair<std::string, const BuildConfig*>>& ligaments)
{
  InputRepairs repairs;
  std::vector<std::string> lines;
  std::vector<std::pair<std::string, TriangleSurface>> bones;
  for (const auto& [name, file] : bone_files) {
    repair::Report report;
    if (auto bone = pipeline::load_bone(file, &report)) {
      bones.emplace_back(name, std::move(*bone));
      repairs.bones[name] = repair::to_json(report);
      for (const std::string& line : repair::describe(report))
        lines.push_back(fmt::format("{} repair: {}", name, line));
    }
  }
  for (const auto& [name, config] : ligaments) {
    repair::Report report;
    const TriangleSurface surface = pipeline::load_ligament(*config, nullptr, &report);
    pipeline::require_a_bone_nearby(name.empty() ? "the ligament" : "ligament " + name, surface,
                                    bones);
    repairs.ligaments[name] = repair::to_json(report);
    for (const std::string& line : repair::describe(report))
      lines.push_back(fmt::format("{}surface repair: {}", name.empty() ? "" : name + " ", line));
  }
  for (const std::string& line : lines)
    log_info(line);
  return repairs;
}

/// A knee config: every ligament built in its own folder of `o.out`, the flags over each.
void run_knee_build_job(const BuildOptions& o, const std::string& target,
                        const nlohmann::json& found_by_name = nullptr)
{
  for (const auto& [flag, value] :
       {std::pair{"--surface", o.surface}, std::pair{"--femur", o.femur},
        std::pair{"--tibia", o.tibia}, std::pair{"--labels", o.labels},
        std::pair{"--ligament-label", o.ligament_label}})
    if (!value.empty())
      fail("{} describes a knee: its surfaces come from the config, not from {}", o.config, flag);
  if (const std::vector<std::string> flags = o.key_flags.given_under("attachments.");
      !flags.empty())
    fail("{} describes a knee: each ligament has its own footprints ([ligament.attachments.femur] "
         "and the distal one), which one flag cannot give ({}); set them in the config, or for "
         "every ligament with --set ligament.attachments.femur.KEY=VALUE",
         o.config, fmt::join(flags, ", "));
  const fs::path out = o.out;
  // Surfaces from a label map are written only once all of them could be made.
  nlohmann::json label_report;
  pipeline::KneeConfig knee = pipeline::knee_surfaces_from_labels(
      pipeline::load_knee_config(o.config, with_flag_assignments(o, "ligament.")), out,
      label_report);
  pipeline::add_anatomy_parts(knee);
  std::vector<std::pair<std::string, const BuildConfig*>> ligaments;
  for (const pipeline::LigamentConfig& ligament : knee.ligaments)
    ligaments.emplace_back(ligament.name, &ligament.build);
  const InputRepairs repairs = read_inputs({{"femur", knee.femur},
                                            {"tibia", knee.tibia},
                                            {"fibula", knee.fibula},
                                            {"patella", knee.patella}},
                                           ligaments);

  RunSummary summary(target == "model" ? "build" : target);
  summary.inputs() = {{"config", o.config}, {"set", o.set}, {"knee", true}};
  summary.parameters() = pipeline::to_json(knee);
  summary.results()["surface_repair"] = repairs.ligaments;
  summary.results()["bone_repair"] = repairs.bones;
  if (!label_report.is_null())
    summary.results()["label_map"] = label_report;
  if (!found_by_name.is_null())
    summary.results()["found_by_name"] = found_by_name;
  pipeline::build_knee(knee, out, target, o.force, summary);
  if (target == "model") {
    report_anatomy(out, !o.no_images);
    summary.results()["cross_sections"] = report_thin_ligaments(knee, out);
  }
  summary.write(out);
  log_info(fmt::format("wrote {}", (out / "summary.json").string()));
}

/// A label map and nothing else: the knee its names describe, its config written as
/// `out/knee.toml` and built as a knee config is.
void run_labelled_knee_job(const BuildOptions& o, const std::string& target)
{
  for (const auto& [flag, value] :
       {std::pair{"--surface", o.surface}, std::pair{"--femur", o.femur},
        std::pair{"--tibia", o.tibia}, std::pair{"--femur-label", o.femur_label},
        std::pair{"--tibia-label", o.tibia_label}})
    if (!value.empty())
      fail("{} with --labels and no --ligament-label: the whole knee is found by its label "
           "names; give --ligament-label to build one ligament, or a knee config",
           flag);
  const fs::path out = o.out;
  const pipeline::KneeFromLabels found = pipeline::knee_from_labels(o.labels, o.colour_table, out);
  for (const nlohmann::json& label : found.labels)
    log_info(fmt::format("label {} ({}): {}", label["label"].get<int>(),
                         fmt::join(label["names"].get<std::vector<std::string>>(), ", "),
                         label["taken_for"].get<std::string>()));
  for (const std::string& note : found.notes)
    log_info(note);
  ensure_directory(out);
  const fs::path config = out / "knee.toml";
  write_text_atomically(config, found.config_text);
  log_info(fmt::format("wrote {}: the knee config this build uses", config.string()));
  BuildOptions knee = o;
  knee.config = config.string();
  knee.labels.clear();
  knee.colour_table.clear();
  try {
    run_knee_build_job(knee, target, {{"labels", found.labels}, {"notes", found.notes}});
  } catch (const InputError& e) {
    fail("{} (the knee the map's names describe is {}: edit it, leaving a ligament out if need "
         "be, and build it with `ligsim build --config {} --out {}` and your other flags)",
         e.what(), config.string(), config.string(), out.string());
  }
}

void run_build_job(const BuildOptions& o, const std::string& target)
{
  if (!o.config.empty() && pipeline::is_knee_config(o.config)) {
    run_knee_build_job(o, target);
    return;
  }
  if (o.config.empty() && !o.labels.empty() && o.ligament_label.empty()) {
    run_labelled_knee_job(o, target);
    return;
  }
  const fs::path out = o.out;
  const bool existed = fs::exists(out);
  // On failure, a folder this run created is left as it was: absent.
  const auto clean_up = [&] {
    std::error_code ignored;
    if (!existed) {
      for (const char* file :
           {pipeline::ligament_from_labels, pipeline::files::femur, pipeline::files::tibia})
        fs::remove(out / file, ignored);
      fs::remove(out / ".ligsim-cache", ignored); // only removes it if empty
      fs::remove(out, ignored);
    }
  };
  // Check every input before the stages run, so bad input leaves nothing behind (surfaces from
  // a label map are written only once all of them could be made).
  nlohmann::json label_report;
  std::string defaults_by_name;
  BuildConfig config;
  InputRepairs repairs;
  try {
    const StageMeter label_meter;
    config = pipeline::surfaces_from_labels(resolve_config(o), out, label_report);
    if (!label_report.is_null())
      label_report["wall_s"] = label_meter.wall_s(); // reading the map, surfaces, writing them
    if (config.labels.empty())
      config.ligament_part = pipeline::part_of_surface(config.surface);
    if (!config.ligament_part.empty()) {
      config.anatomy.parts[config.ligament_part] = config.surface;
      const std::string used = pipeline::apply_part_defaults(config);
      if (!used.empty()) {
        log_info(fmt::format("the ligament's {} names the {}: {}",
                             config.labels.empty() ? "surface" : "label", config.ligament_part,
                             used));
        defaults_by_name = used;
      }
    }
    repairs = read_inputs({{"femur", config.femur}, {"tibia", config.tibia}}, {{"", &config}});
  } catch (const Error&) {
    clean_up();
    throw;
  }

  RunSummary summary(target == "model" ? "build" : target);
  summary.inputs() = {{"config", o.config},
                      {"set", o.set},
                      {"surface", config.surface.string()},
                      {"femur", config.femur.string()},
                      {"tibia", config.tibia.string()},
                      {"labels", config.labels.string()}};
  summary.parameters() = pipeline::to_json(config);
  summary.results()["surface_repair"] = repairs.ligaments.at("");
  summary.results()["bone_repair"] = repairs.bones;
  if (!label_report.is_null())
    summary.results()["label_map"] = label_report;
  if (!defaults_by_name.empty())
    summary.results()["defaults_by_name"] = {{"ligament", config.ligament_part},
                                             {"used", defaults_by_name}};
  try {
    pipeline::run_target(config, out, target, o.force, summary);
    if (target == "model")
      pipeline::build_companion(config, out, o.force, summary);
  } catch (const Error&) {
    clean_up();
    throw;
  }
  report_anatomy(out, !o.no_images);
  summary.write(out);
  log_info(fmt::format("wrote {}", (out / "summary.json").string()));
}

} // namespace

void add_build_commands(CLI::App& app)
{
  auto* build = app.add_subcommand("build", "run every model-building stage that is not current: "
                                            "surface -> model.vtu + scene.toml");
  auto build_options = std::make_shared<BuildOptions>();
  add_options(build, *build_options);
  build->callback([build_options] { run_build_job(*build_options, "model"); });

  for (const pipeline::Stage& stage : pipeline::build_stages()) {
    auto* command = app.add_subcommand(
        stage.name, fmt::format("stage: {} (runs the stages it needs that are not current)",
                                stage.description));
    auto options = std::make_shared<BuildOptions>();
    add_options(command, *options);
    command->callback([options, name = stage.name] { run_build_job(*options, name); });
  }
}

} // namespace ligsim::cli
