#include "pipeline/stage_graph/knee_config.hpp"

#include "common/error.hpp"
#include "pipeline/stage_graph/config_section.hpp"
#include "pipeline/stage_graph/ligament_defaults.hpp"
#include "stages/anatomy/part_names.hpp"

#include <algorithm>
#include <set>

namespace ligsim::pipeline {

namespace fs = std::filesystem;
using namespace config_reading;

namespace {

/// A name that is a folder name on every system: letters, digits, '-' and '_'.
bool plain_name(const std::string& name)
{
  return !name.empty() && std::all_of(name.begin(), name.end(), [](unsigned char c) {
    return std::isalnum(c) || c == '-' || c == '_';
  });
}

LigamentConfig read_ligament(const toml::table& table, std::size_t index, const KneeConfig& knee)
{
  const fs::path& file = knee.file;
  const std::string where = fmt::format("ligament {}", index + 1);
  Section entry(&table, where, file);
  LigamentConfig ligament;
  entry.read("name", ligament.name);
  if (!plain_name(ligament.name))
    fail("{}:{}: [[ligament]] {} needs a name of letters, digits, '-' or '_' (its output "
         "folder), got \"{}\"",
         file.string(), table.source().begin.line, index + 1, ligament.name);

  // Its defaults by name, then the knee's shared sections, then its own.
  ligament.build = knee.shared;
  const auto defaults = ligament_defaults(ligament.name);
  if (defaults) {
    ligament.build.material = defaults->material;
    ligament.failure_strain = defaults->failure_strain;
    ligament.failure_load_n = defaults->failure_load_n;
    ligament.defaults_source = defaults->material_source + "; " + defaults->failure_source;
  } else {
    ligament.defaults_source = "not a ligament with published defaults (MCL, LCL, ACL, PCL): "
                               "the MCL's material and failure figures";
  }
  entry.read("failure_strain", ligament.failure_strain);
  entry.read("failure_load_n", ligament.failure_load_n);
  entry.read("contact_bones", ligament.contact_bones);
  for (const std::string& bone : ligament.contact_bones)
    if (bone != "femur" && bone != "tibia" && bone != "fibula")
      fail("{}:{}: ligament {}: contact_bones lists \"{}\"; the knee's bones are femur, tibia "
           "and fibula",
           file.string(), table.source().begin.line, ligament.name, bone);
  for (const char* name : {"input", "attachments", "material"})
    entry.allow(name);
  for (const std::string& name : stage_section_names())
    entry.allow(name);
  entry.reject_unknown();
  if (!(ligament.failure_strain > 0.0) || !(ligament.failure_load_n > 0.0))
    fail("{}:{}: ligament {}: failure_strain and failure_load_n must be positive", file.string(),
         table.source().begin.line, ligament.name);

  const std::string prefix = "ligament." + ligament.name + ".";
  Section input(table_at(&table, "input"), prefix + "input", file);
  ligament.build.surface.clear();
  input.read_path("surface", ligament.build.surface);
  input.read_label("label", ligament.build.ligament_label);
  input.read("strict", ligament.build.strict);
  input.reject_unknown();
  const bool labelled = !knee.labels.empty();
  if (!labelled && !ligament.build.ligament_label.empty())
    fail("{}:{}: ligament {} gives a label, but the knee's [input] gives no label map (labels)",
         file.string(), table.source().begin.line, ligament.name);
  if (!labelled && ligament.build.surface.empty())
    fail("{}:{}: ligament {} has no surface: give [ligament.input] surface (a file, or a glTF "
         "file with #MESH)",
         file.string(), table.source().begin.line, ligament.name);
  if (labelled && (ligament.build.ligament_label.empty() || !ligament.build.surface.empty()))
    fail("{}:{}: ligament {}: the knee's surfaces come from the label map {}, so give its "
         "[ligament.input] label (a number or a name) and no surface",
         file.string(), table.source().begin.line, ligament.name, knee.labels.string());

  // The footprints its name places where the config gives none (the LCL's on the fibula when the
  // knee has one).
  const toml::table* given = table_at(&table, "attachments");
  const auto gives = [&](const char* bone) { return given != nullptr && given->contains(bone); };
  std::vector<std::string> distal_bones = {"tibia", "fibula"};
  if (defaults) {
    const bool has_fibula = !knee.fibula.empty() || !knee.fibula_label.empty();
    if (!gives("femur"))
      ligament.build.femur_attachment = defaults->femur_footprint;
    if (!gives("tibia") && !gives("fibula") && (defaults->distal_bone == "tibia" || has_fibula)) {
      ligament.build.tibia_attachment = defaults->distal_footprint;
      if (defaults->distal_bone == "fibula")
        distal_bones = {"fibula", "tibia"};
    }
    ligament.defaults_source +=
        "; footprints where the config gives none: " + defaults->footprint_source;
  }
  ligament.distal_bone =
      read_attachment_sections(table, prefix, file, distal_bones, ligament.build);
  read_stage_sections(table, prefix, file, ligament.build);
  read_material_section(table, prefix, file, ligament.build);
  const bool fibula = ligament.distal_bone == "fibula";
  const fs::path& distal = fibula ? knee.fibula : knee.tibia;
  const std::string& distal_label = fibula ? knee.fibula_label : knee.tibia_label;
  if (distal.empty() && distal_label.empty())
    fail("{}:{}: ligament {} attaches to the {}, but [input] gives no {} surface", file.string(),
         table.source().begin.line, ligament.name, ligament.distal_bone, ligament.distal_bone);
  ligament.build.tibia = distal;
  return ligament;
}

} // namespace

void add_anatomy_parts(KneeConfig& knee)
{
  // The knee's tibia too: a ligament on the fibula has the fibula as its own distal bone.
  std::map<std::string, fs::path> parts = {{"tibia", knee.tibia}};
  if (!knee.fibula.empty())
    parts["fibula"] = knee.fibula;
  if (!knee.patella.empty())
    parts["patella"] = knee.patella;
  for (const LigamentConfig& ligament : knee.ligaments)
    if (const auto part = anatomy::recognise_part(ligament.name);
        part && anatomy::is_ligament(*part))
      parts[anatomy::part_name(*part)] = ligament.build.surface;
  knee.shared.anatomy.parts = parts;
  for (LigamentConfig& ligament : knee.ligaments)
    ligament.build.anatomy.parts = parts;
}

bool is_knee_config(const fs::path& file)
{
  return parse_config_file(file).contains("ligament");
}

KneeConfig load_knee_config(const fs::path& file, const std::vector<std::string>& overrides)
{
  const toml::table root = parse_config_file(file, overrides);
  KneeConfig knee;
  knee.file = file;
  Section top(&root, "top level", file);
  for (const char* name : {"input", "anatomy", "ligament"})
    top.allow(name);
  for (const std::string& name : stage_section_names())
    top.allow(name);
  if (root.contains("material") || root.contains("attachments"))
    fail("{}: a knee config gives [material] and [attachments] per ligament "
         "([ligament.material], [ligament.attachments.femur], ...)",
         file.string());
  top.reject_unknown();

  Section input(table_at(&root, "input"), "input", file);
  input.read_path("femur", knee.femur);
  input.read_path("tibia", knee.tibia);
  input.read_path("fibula", knee.fibula);
  input.read_path("patella", knee.patella);
  input.read_path("labels", knee.labels);
  input.read_path("colour_table", knee.colour_table);
  input.read_label("femur_label", knee.femur_label);
  input.read_label("tibia_label", knee.tibia_label);
  input.read_label("fibula_label", knee.fibula_label);
  input.read_label("patella_label", knee.patella_label);
  input.read("strict", knee.shared.strict);
  input.reject_unknown();
  if (!knee.labels.empty()) {
    if (!knee.femur.empty() || !knee.tibia.empty() || !knee.fibula.empty() || !knee.patella.empty())
      fail("{}: [input] gives a label map (labels) and bone surfaces: give the bones' labels "
           "(femur_label, tibia_label, fibula_label) instead of their files",
           file.string());
    // A map without a femur builds (the femoral footprints are then the ligaments' ends), but
    // cannot be flexed: the flexion says so.
    if (knee.tibia_label.empty())
      fail("{}: a knee from a label map needs the tibia's label ([input] tibia_label; and the "
           "femur's, femur_label, to be flexed)",
           file.string());
  } else if (!knee.femur_label.empty() || !knee.tibia_label.empty() || !knee.fibula_label.empty() ||
             !knee.patella_label.empty() || !knee.colour_table.empty()) {
    fail("{}: [input] gives bone labels or a colour table but no label map (labels)",
         file.string());
  } else if (knee.femur.empty() || knee.tibia.empty()) {
    fail("{}: a knee config needs the femur and the tibia ([input] femur and tibia, or a label "
         "map: labels, femur_label, tibia_label)",
         file.string());
  }
  knee.shared.femur = knee.femur;
  knee.shared.tibia = knee.tibia;
  read_anatomy_section(root, file, knee.shared);
  read_stage_sections(root, "", file, knee.shared);

  const toml::array* ligaments = root.get_as<toml::array>("ligament");
  if (ligaments == nullptr || ligaments->empty() || !ligaments->is_array_of_tables())
    fail("{}: `ligament` must be an array of tables: one [[ligament]] per ligament", file.string());
  std::set<std::string> names;
  for (std::size_t i = 0; i < ligaments->size(); ++i) {
    LigamentConfig ligament = read_ligament(*ligaments->get(i)->as_table(), i, knee);
    if (!names.insert(ligament.name).second)
      fail("{}: two ligaments are called {}: each needs its own name (its output folder)",
           file.string(), ligament.name);
    knee.ligaments.push_back(std::move(ligament));
  }
  return knee;
}

} // namespace ligsim::pipeline
