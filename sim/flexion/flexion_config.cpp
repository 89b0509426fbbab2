#include "sim/flexion/flexion_config.hpp"

#include "common/config_section.hpp"
#include "common/error.hpp"
#include "common/toml_overrides.hpp"
#include "common/toml_table.hpp"
#include "sim/flexion/flexion_fields.hpp"

namespace ligsim::sim {

namespace fs = std::filesystem;

namespace {

/// Reads one table's keys of its visit list over `settings`.
template <class S, class VisitFields>
void read_table_fields(TomlTable& table, S& settings, VisitFields visit)
{
  ConfigSection section(table);
  visit(settings, FieldReader{section});
}

/// What each table checks beyond its keys' types, and the keys read by hand.
void check_table(const std::string& name, TomlTable& table, const fs::path& base,
                 FlexionSettings& settings)
{
  if (name == "axis") {
    if (settings.axis.source == AxisSettings::Source::points && !table.has("first_mm") &&
        !table.has("second_mm"))
      table.fail_at("method", "method \"points\" needs first_mm and second_mm");
  } else if (name == "anatomy") {
    const std::string& side = settings.anatomy.side;
    if (table.has("side") && side != "left" && side != "right")
      table.fail_at("side", "expected \"left\" or \"right\", got \"" + side + "\"");
  } else if (name == "motion") {
    MotionSettings& motion = settings.motion;
    if (table.has("table"))
      motion.table = base / table.text("table", "");
    if (motion.path == MotionSettings::Path::table && motion.table.empty())
      table.fail_at("path", "path \"table\" needs `table`, the CSV file");
  } else if (name == "ligament") {
    for (const std::string& key : table.keys())
      settings.given.insert("ligament." + key);
    if (!(settings.ligament.strain_region_radius_mm > 0.0))
      table.fail_at("strain_region_radius_mm", "the region radius must be a positive number of mm");
  } else if (name == "material") {
    // A table with in_situ_strain alone leaves each ligament's material as it was built.
    for (const std::string& key : table.keys())
      settings.given.insert(key == "in_situ_strain" ? "in_situ_strain" : "material");
  } else if (name == "contact") {
    for (const std::string& bone : settings.contact.bones)
      if (bone != "femur" && bone != "tibia" && bone != "fibula")
        table.fail_at("bones",
                      "expected \"femur\", \"tibia\" and/or \"fibula\", got \"" + bone + "\"");
    if (!table.has("band_mm"))
      widen_band_to_barrier(settings.contact);
  } else if (name == "articular") {
    if (const auto problem = articular_problem(settings.free.articular))
      table.fail_at(problem->key, problem->what);
  } else if (name == "free") {
    const FreeKneeSettings& free = settings.free;
    if (!(free.tolerance > 0.0) || free.max_iterations < 1 || !(free.rotation_scale_mm > 0.0) ||
        !(free.max_step_mm > 0.0) || !(free.max_translation_mm > 0.0) ||
        !(free.max_rotation_deg > 0.0))
      table.fail_at("tolerance", "tolerance, max_iterations, rotation_scale_mm, max_step_mm, "
                                 "max_translation_mm and max_rotation_deg must be positive");
  }
}

/// Reads the parsed config `document` over `settings`.
void read_document(const toml::table& document, const fs::path& base, const std::string& name,
                   FlexionSettings& settings)
{
  TomlTable root(document, name);
  if (root.has("model"))
    settings.model_dir = base / root.text("model", "");
  visit_flexion_tables(settings, [&](const std::string& table_name, auto& part, auto visit) {
    if (table_name.empty()) {
      read_table_fields(root, part, visit);
      return;
    }
    if (auto table = root.table(table_name)) {
      read_table_fields(*table, part, visit);
      check_table(table_name, *table, base, settings);
      table->reject_unknown_keys();
    }
  });
  root.reject_unknown_keys();
}

} // namespace

void parse_flexion_config(const std::string& text, const fs::path& base, const std::string& name,
                          FlexionSettings& settings)
{
  read_document(parse_toml(text, name), base, name, settings);
}

void read_flexion_config(const fs::path& file, FlexionSettings& settings,
                         const std::vector<std::string>& overrides)
{
  toml::table document;
  if (!file.empty())
    document = parse_toml(read_text_file(file, "flexion config"), file.string());
  apply_overrides(document, overrides);
  read_document(document, file.parent_path(), file.empty() ? "--set" : file.string(), settings);
}

} // namespace ligsim::sim
