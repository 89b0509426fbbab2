#include "pipeline/stage_graph/build_config.hpp"

#include "common/error.hpp"
#include "common/fields_json.hpp"
#include "common/knee_manifest.hpp"
#include "common/progress.hpp"
#include "common/toml_overrides.hpp"
#include "pipeline/stage_graph/config_fields.hpp"
#include "pipeline/stage_graph/config_section.hpp"
#include "pipeline/stage_graph/ligament_defaults.hpp"
#include "stages/anatomy/part_names.hpp"
#include "stages/io/surface_path.hpp"

#include <fmt/format.h>

#include <string_view>

namespace ligsim::pipeline {

namespace fs = std::filesystem;

namespace config_reading {

toml::table parse_config_file(const fs::path& file, const std::vector<std::string>& overrides)
{
  toml::table root;
  if (!file.empty()) {
    if (!fs::is_regular_file(file))
      fail("missing config file '{}'", file.string());
    try {
      root = toml::parse_file(file.string());
    } catch (const toml::parse_error& e) {
      fail("{}:{}: {}", file.string(), e.source().begin.line, e.description());
    }
  }
  apply_overrides(root, overrides);
  return root;
}

void read_stage_sections(const toml::table& table, const std::string& prefix, const fs::path& file,
                         BuildConfig& config)
{
  read_fields(&table, "voxelize", prefix + "voxelize", file, config.voxelize,
              [](auto& p, auto&& v) { visit_voxelize(p, v); });
  read_fields(&table, "centerline", prefix + "centerline", file, config.centerline,
              [](auto& p, auto&& v) { visit_centerline(p, v); });
  read_fields(&table, "field", prefix + "field", file, config.field,
              [](auto& p, auto&& v) { visit_field(p, v); });
  read_fields(&table, "tetmesh", prefix + "tetmesh", file, config.tetmesh,
              [](auto& p, auto&& v) { visit_tetmesh(p, v); });
  read_fields(&table, "fibers", prefix + "fibers", file, config.fibers,
              [](auto& p, auto&& v) { visit_fibers(p, v); });
  read_fields(&table, "model", prefix + "model", file, config.model,
              [](auto& p, auto&& v) { visit_model(p, v); });
  read_fields(&table, "error_estimate", prefix + "error_estimate", file, config.error_estimate,
              [](auto& p, auto&& v) { visit_error_estimate(p, v); });
  const double scale = config.error_estimate.mesh_scale;
  if (scale != 0.0 && !(scale >= companion_min_size_ratio && scale <= 4.0))
    fail("{}: [{}error_estimate] mesh_scale must be 0 (no estimate) or from {} to 4, got {}",
         file.string(), prefix, companion_min_size_ratio, scale);
  read_fields(&table, "flexion", prefix + "flexion", file, config.flexion,
              [](auto& p, auto&& v) { visit_flexion(p, v); });
  if (const toml::table* flexion = table_at(&table, "flexion"))
    config.flexion.axis_given = config.flexion.axis_given || flexion->contains("axis_point_mm") ||
                                flexion->contains("axis_direction");
}

void read_anatomy_section(const toml::table& table, const fs::path& file, BuildConfig& config)
{
  read_fields(&table, "anatomy", "anatomy", file, config.anatomy,
              [](auto& p, auto&& v) { visit_anatomy(p, v); });
  if (!config.anatomy.side.empty() && config.anatomy.side != "left" &&
      config.anatomy.side != "right")
    fail("{}: [anatomy] side must be \"left\" or \"right\", got \"{}\"", file.string(),
         config.anatomy.side);
  for (std::string* surface :
       {&config.anatomy.medial_epicondyle_surface, &config.anatomy.lateral_epicondyle_surface})
    *surface = relative_to(file, *surface);
}

std::string read_attachment_sections(const toml::table& table, const std::string& prefix,
                                     const fs::path& file,
                                     const std::vector<std::string>& distal_bones,
                                     BuildConfig& config)
{
  const toml::table* attachments = table_at(&table, "attachments");
  Section attachment_section(attachments, prefix + "attachments", file);
  attachment_section.allow("femur");
  std::string distal;
  for (const std::string& bone : distal_bones) {
    attachment_section.allow(bone);
    if (attachment_section.has(bone)) {
      if (!distal.empty())
        fail("{}: [{}attachments] gives both {} and {}: the ligament's distal footprint lies on "
             "one bone",
             file.string(), prefix, distal, bone);
      distal = bone;
    }
  }
  attachment_section.reject_unknown();
  if (distal.empty())
    distal = distal_bones.front();
  const auto rule = [](auto& r, auto&& visit) { visit_rule(r, visit); };
  read_fields(attachments, "femur", prefix + "attachments.femur", file, config.femur_attachment,
              rule);
  read_fields(attachments, distal.c_str(), prefix + "attachments." + distal, file,
              config.tibia_attachment, rule);
  for (attachments::Rule* r : {&config.femur_attachment, &config.tibia_attachment})
    r->patch = relative_to(file, r->patch);
  return distal;
}

namespace {

/// The names a build config's [material] gave two keys before it took the simulator's: a config
/// that gives one is read as the key, with a note, so that it keeps working as written.
struct FormerName {
  std::string_view key;
  const char* former;
};
constexpr FormerName former_material_names[] = {{"k_mpa", "bulk_modulus_mpa"},
                                                {"convention", "fiber_convention"}};

/// FieldReader that reads a key under its former name where the table gives that.
struct FormerNameReader {
  ConfigSection& section;

  template <class Value> void operator()(const char* key, Value&& value)
  {
    for (const FormerName& name : former_material_names) {
      if (name.key != key || !section.has(name.former))
        continue;
      if (section.has(key))
        section.fail_at(name.former,
                        fmt::format("the former name of {}, which the table gives too: give one "
                                    "(--set over such a file: set the name the file uses)",
                                    key));
      log_info(fmt::format("note: {}: {} is now called {}; read as {}", section.where(),
                           name.former, key, key));
      FieldReader{section}(name.former, std::forward<Value>(value));
      return;
    }
    FieldReader{section}(key, std::forward<Value>(value));
  }
};

} // namespace

void read_material_section(const toml::table& table, const std::string& prefix,
                           const fs::path& file, BuildConfig& config)
{
  ConfigSection section(table_at(&table, "material"), prefix + "material", file);
  visit_material(config.material, FormerNameReader{section});
  section.reject_unknown();
}

} // namespace config_reading

using namespace config_reading;

BuildConfig load_build_config(const fs::path& given, const std::vector<std::string>& overrides)
{
  const toml::table root = parse_config_file(given, overrides);
  // Without a file, messages name the settings; relative paths stay relative to here.
  const fs::path file = given.empty() ? fs::path("--set") : given;
  if (root.contains("ligament"))
    fail("{}: this config describes a knee ([[ligament]] tables): `ligsim build` takes it; "
         "this command takes one ligament's config",
         file.string());

  BuildConfig config;
  Section top(&root, "top level", file);
  for (const char* name : {"input", "anatomy", "attachments", "material"})
    top.allow(name);
  for (const std::string& name : stage_section_names())
    top.allow(name);
  top.reject_unknown();

  Section input(table_at(&root, "input"), "input", file);
  input.read_path("surface", config.surface);
  input.read_path("femur", config.femur);
  input.read_path("tibia", config.tibia);
  input.read("strict", config.strict);
  input.read_path("labels", config.labels);
  input.read_path("colour_table", config.colour_table);
  for (auto [key, target] : {std::pair{"ligament_label", &config.ligament_label},
                             std::pair{"femur_label", &config.femur_label},
                             std::pair{"tibia_label", &config.tibia_label}})
    input.read_label(key, *target);
  input.reject_unknown();

  read_anatomy_section(root, file, config);
  read_attachment_sections(root, "", file, {"tibia"}, config);
  read_stage_sections(root, "", file, config);
  read_material_section(root, "", file, config);
  if (root.contains("material"))
    config.given.insert("material");
  if (const toml::table* attachments = table_at(&root, "attachments"))
    for (const char* bone : {"femur", "tibia"})
      if (attachments->contains(bone))
        config.given.insert(std::string("attachments.") + bone);
  return config;
}

std::string part_of_surface(const fs::path& surface)
{
  const io::SurfacePath source = io::split_surface_path(surface);
  const std::string name = source.mesh.empty() ? source.file.stem().string() : source.mesh;
  const auto part = anatomy::recognise_part(name);
  return part && anatomy::is_ligament(*part) ? anatomy::part_name(*part) : "";
}

std::string apply_part_defaults(BuildConfig& config)
{
  const auto defaults = ligament_defaults(config.ligament_part);
  if (config.ligament_part.empty() || !defaults)
    return "";
  std::string used;
  const auto note = [&](const std::string& what) { used += (used.empty() ? "" : "; ") + what; };
  if (!config.given.count("material")) {
    config.material = defaults->material;
    note("material: " + defaults->material_source);
  }
  if (!config.given.count("attachments.femur")) {
    config.femur_attachment = defaults->femur_footprint;
    note("femoral footprint by the " + config.ligament_part + "'s name");
  }
  // A one-ligament build's distal bone is the tibia: only a tibial footprint's rule carries over.
  if (!config.given.count("attachments.tibia") && defaults->distal_bone == "tibia") {
    config.tibia_attachment = defaults->distal_footprint;
    note("tibial footprint by the " + config.ligament_part + "'s name");
  }
  if (!used.empty())
    note("footprints: " + defaults->footprint_source);
  return used;
}

namespace {

std::string path_text(const fs::path& path)
{
  return path.empty() ? "" : path.string();
}

} // namespace

nlohmann::json stage_parameters(const BuildConfig& c, const std::string& stage)
{
  const auto rule = [](auto& r, auto&& visit) { visit_rule(r, visit); };
  if (stage == "anatomy") {
    nlohmann::json anatomy = as_json(c.anatomy, [](auto& p, auto&& v) { visit_anatomy(p, v); });
    anatomy["label_map_frame"] = c.label_frame_anatomical;
    if (c.anatomy.known)
      anatomy["known"] = to_json(*c.anatomy.known);
    anatomy["parts"] = nlohmann::json::array();
    for (const auto& [name, file] : c.anatomy.parts)
      anatomy["parts"].push_back(name); // their contents are the stage's input files
    return anatomy;
  }
  if (stage == "attachments")
    return {{"femur", as_json(c.femur_attachment, rule)},
            {"tibia", as_json(c.tibia_attachment, rule)}};
  if (stage == "distance")
    return nlohmann::json::object(); // exact distances: nothing to choose
  if (stage == "voxelize")
    return as_json(c.voxelize, [](auto& p, auto&& v) { visit_voxelize(p, v); });
  if (stage == "centerline")
    return as_json(c.centerline, [](auto& p, auto&& v) { visit_centerline(p, v); });
  if (stage == "field")
    return as_json(c.field, [](auto& p, auto&& v) { visit_field(p, v); });
  if (stage == "tetmesh")
    return as_json(c.tetmesh, [](auto& p, auto&& v) { visit_tetmesh(p, v); });
  if (stage == "fibers")
    return as_json(c.fibers, [](auto& p, auto&& v) { visit_fibers(p, v); });
  if (stage == "model") {
    nlohmann::json model = as_json(c.model, [](auto& p, auto&& v) { visit_model(p, v); });
    model["material"] = material_json(c.material);
    model["flexion"] = as_json(c.flexion, [](auto& p, auto&& v) { visit_flexion(p, v); });
    model["flexion"]["axis_given"] = c.flexion.axis_given;
    return model;
  }
  fail("unknown stage '{}'", stage);
}

nlohmann::json material_json(const sim::MaterialParameters& material)
{
  return as_json(material, [](auto& p, auto&& v) { visit_material(p, v); });
}

nlohmann::json to_json(const BuildConfig& c)
{
  nlohmann::json all = {
      {"surface", path_text(c.surface)},    {"femur", path_text(c.femur)},
      {"tibia", path_text(c.tibia)},        {"strict", c.strict},
      {"labels", path_text(c.labels)},      {"colour_table", path_text(c.colour_table)},
      {"ligament_label", c.ligament_label}, {"femur_label", c.femur_label},
      {"tibia_label", c.tibia_label}};
  for (const char* stage : {"anatomy", "attachments", "voxelize", "distance", "centerline", "field",
                            "tetmesh", "fibers", "model"})
    all[stage] = stage_parameters(c, stage);
  all["error_estimate"] =
      as_json(c.error_estimate, [](auto& p, auto&& v) { visit_error_estimate(p, v); });
  return all;
}

} // namespace ligsim::pipeline
