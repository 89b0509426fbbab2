#include "sim/flexion/flexion_config.hpp"

#include "common/error.hpp"
#include "common/toml_overrides.hpp"
#include "common/toml_table.hpp"
#include "sim/scene/contact_table.hpp"

namespace ligsim::sim {

namespace fs = std::filesystem;

namespace {

void read_axis(TomlTable& table, AxisSettings& axis)
{
  const std::string method = table.text("method", to_string(axis.source));
  if (method == "points")
    axis.source = AxisSettings::Source::points;
  else if (method == "condyles")
    axis.source = AxisSettings::Source::condyles;
  else if (method == "transepicondylar")
    axis.source = AxisSettings::Source::transepicondylar;
  else
    table.fail_at("method", "expected \"condyles\", \"transepicondylar\" or \"points\", got \"" +
                                method + "\"");
  axis.first_mm = table.vector3("first_mm", axis.first_mm);
  axis.second_mm = table.vector3("second_mm", axis.second_mm);
  axis.posterior = table.vector3("posterior", axis.posterior);
  axis.medial_epicondyle_mm = table.vector3("medial_epicondyle_mm", axis.medial_epicondyle_mm);
  axis.lateral_epicondyle_mm = table.vector3("lateral_epicondyle_mm", axis.lateral_epicondyle_mm);
  if (axis.source == AxisSettings::Source::points && !table.has("first_mm") &&
      !table.has("second_mm"))
    table.fail_at("method", "method \"points\" needs first_mm and second_mm");
  table.reject_unknown_keys();
}

void read_anatomy(TomlTable& table, AnatomySettings& anatomy)
{
  anatomy.side = table.text("side", anatomy.side);
  if (table.has("side") && anatomy.side != "left" && anatomy.side != "right")
    table.fail_at("side", "expected \"left\" or \"right\", got \"" + anatomy.side + "\"");
  anatomy.proximal = table.vector3("proximal", anatomy.proximal);
  anatomy.posterior = table.vector3("posterior", anatomy.posterior);
  table.reject_unknown_keys();
}

void read_motion(TomlTable& table, const fs::path& base, MotionSettings& motion)
{
  const std::string path = table.text("path", to_string(motion.path));
  if (path == "auto")
    motion.path = MotionSettings::Path::automatic;
  else if (path == "pure")
    motion.path = MotionSettings::Path::pure;
  else if (path == "passive")
    motion.path = MotionSettings::Path::passive;
  else if (path == "table")
    motion.path = MotionSettings::Path::table;
  else if (path == "free")
    motion.path = MotionSettings::Path::free;
  else
    table.fail_at("path", "expected \"auto\", \"free\", \"pure\", \"passive\" or \"table\", "
                          "got \"" +
                              path + "\"");
  motion.coupled_translations = table.boolean("coupled_translations", motion.coupled_translations);
  if (table.has("table"))
    motion.table = base / table.text("table", "");
  if (motion.path == MotionSettings::Path::table && motion.table.empty())
    table.fail_at("path", "path \"table\" needs `table`, the CSV file");
  table.reject_unknown_keys();
}

void read_ligament(TomlTable& table, LigamentSettings& ligament, std::set<std::string>& given)
{
  for (const char* key : {"name", "failure_strain", "failure_load_n", "strain_region_radius_mm"})
    if (table.has(key))
      given.insert(std::string("ligament.") + key);
  ligament.name = table.text("name", ligament.name);
  ligament.failure_strain = table.number("failure_strain", ligament.failure_strain);
  ligament.failure_load_n = table.number("failure_load_n", ligament.failure_load_n);
  ligament.strain_region_radius_mm =
      table.number("strain_region_radius_mm", ligament.strain_region_radius_mm);
  if (!(ligament.strain_region_radius_mm > 0.0))
    table.fail_at("strain_region_radius_mm", "the region radius must be a positive number of mm");
  table.reject_unknown_keys();
}

void read_material(TomlTable& table, FlexionSettings& settings)
{
  // A table with in_situ_strain alone leaves each ligament's material as it was built.
  for (const std::string& key : table.keys())
    settings.given.insert(key == "in_situ_strain" ? "in_situ_strain" : "material");
  MaterialParameters& material = settings.material;
  FiberParameters& fiber = *material.fiber;
  material.mu_mpa = table.number("mu_mpa", material.mu_mpa);
  material.bulk_modulus_mpa = table.number("k_mpa", material.bulk_modulus_mpa);
  if (table.has("volumetric"))
    material.volumetric = parse_volumetric_law(table.text("volumetric", ""), table.where());
  fiber.c3_mpa = table.number("c3_mpa", fiber.c3_mpa);
  fiber.c4 = table.number("c4", fiber.c4);
  fiber.c5_mpa = table.number("c5_mpa", fiber.c5_mpa);
  fiber.lambda_star = table.number("lambda_star", fiber.lambda_star);
  if (table.has("convention"))
    fiber.convention = parse_fiber_convention(table.text("convention", ""), table.where());
  settings.in_situ_strain = table.number("in_situ_strain", settings.in_situ_strain);
  table.reject_unknown_keys();
}

void read_static(TomlTable& table, NewtonSettings& newton)
{
  newton.residual_tolerance = table.number("residual_tolerance", newton.residual_tolerance);
  newton.max_iterations = table.integer("max_iterations", newton.max_iterations);
  newton.max_cutbacks = table.integer("max_cutbacks", newton.max_cutbacks);
  newton.max_substeps = table.integer("max_substeps", newton.max_substeps);
  newton.verbose = table.boolean("verbose", newton.verbose);
  if (table.has("linear_solver"))
    newton.linear_solver = parse_linear_solver(table.text("linear_solver", ""), table.where());
  table.reject_unknown_keys();
}

void read_interactive(TomlTable& table, InteractiveSettings& interactive)
{
  interactive.angular_speed_deg_s =
      table.number("angular_speed_deg_s", interactive.angular_speed_deg_s);
  interactive.time_step_s = table.number("time_step_s", interactive.time_step_s);
  interactive.density_kg_m3 = table.number("density_kg_m3", interactive.density_kg_m3);
  interactive.mass_damping_per_s =
      table.number("mass_damping_per_s", interactive.mass_damping_per_s);
  if (table.has("linear_solver"))
    interactive.linear_solver = parse_linear_solver(table.text("linear_solver", ""), table.where());
  interactive.max_iterations = table.integer("max_iterations", interactive.max_iterations);
  interactive.iteration_tolerance =
      table.number("iteration_tolerance", interactive.iteration_tolerance);
  table.reject_unknown_keys();
}

void read_loads(TomlTable& table, JointLoads& loads)
{
  loads.compression_n = table.number("compression_n", loads.compression_n);
  loads.anterior_n = table.number("anterior_n", loads.anterior_n);
  loads.valgus_nm = table.number("valgus_nm", loads.valgus_nm);
  loads.internal_nm = table.number("internal_nm", loads.internal_nm);
  table.reject_unknown_keys();
}

void read_articular(TomlTable& table, FreeKneeSettings& free)
{
  free.articular_contact = table.boolean("enabled", free.articular_contact);
  ArticularSettings& a = free.articular;
  a.modulus_mpa = table.number("modulus_mpa", a.modulus_mpa);
  a.poisson = table.number("poisson", a.poisson);
  a.thickness_mm = table.number("thickness_mm", a.thickness_mm);
  a.gap_mm = table.number("gap_mm", a.gap_mm);
  a.seated = table.boolean("seated", a.seated);
  if (const auto problem = articular_problem(a))
    table.fail_at(problem->key, problem->what);
  table.reject_unknown_keys();
}

void read_free(TomlTable& table, FreeKneeSettings& free)
{
  free.tolerance = table.number("tolerance", free.tolerance);
  free.max_iterations = table.integer("max_iterations", free.max_iterations);
  free.rotation_scale_mm = table.number("rotation_scale_mm", free.rotation_scale_mm);
  free.max_step_mm = table.number("max_step_mm", free.max_step_mm);
  free.max_translation_mm = table.number("max_translation_mm", free.max_translation_mm);
  free.max_rotation_deg = table.number("max_rotation_deg", free.max_rotation_deg);
  if (!(free.tolerance > 0.0) || free.max_iterations < 1 || !(free.rotation_scale_mm > 0.0) ||
      !(free.max_step_mm > 0.0) || !(free.max_translation_mm > 0.0) ||
      !(free.max_rotation_deg > 0.0))
    table.fail_at("tolerance", "tolerance, max_iterations, rotation_scale_mm, max_step_mm, "
                               "max_translation_mm and max_rotation_deg must be positive");
  table.reject_unknown_keys();
}

void read_contact(TomlTable& table, ContactConfig& contact)
{
  read_contact_table(table, contact);
  if (table.has("bones")) {
    contact.bones = table.texts("bones");
    for (const std::string& bone : contact.bones)
      if (bone != "femur" && bone != "tibia" && bone != "fibula")
        table.fail_at("bones",
                      "expected \"femur\", \"tibia\" and/or \"fibula\", got \"" + bone + "\"");
  }
  if (table.has("initial_overlap")) {
    const std::string overlap = table.text("initial_overlap", "");
    if (overlap != "deform" && overlap != "reshape")
      table.fail_at("initial_overlap",
                    "expected \"deform\" or \"reshape\", got \"" + overlap + "\"");
    contact.reshape_overlap = overlap == "reshape";
  }
  table.reject_unknown_keys();
}

/// Reads the parsed config `document` over `settings`.
void read_document(const toml::table& document, const fs::path& base, const std::string& name,
                   FlexionSettings& settings)
{
  TomlTable root(document, name);
  if (root.has("model"))
    settings.model_dir = base / root.text("model", "");
  if (root.has("angles_deg"))
    settings.angles_deg = root.numbers("angles_deg");
  if (root.has("mode")) {
    const std::string mode = root.text("mode", "");
    if (mode == "static")
      settings.mode = FlexionMode::quasi_static;
    else if (mode == "interactive")
      settings.mode = FlexionMode::interactive;
    else
      root.fail_at("mode", "expected \"static\" or \"interactive\", got \"" + mode + "\"");
  }
  settings.images = root.boolean("images", settings.images);
  if (root.has("image_angles_deg"))
    settings.image_angles_deg = root.numbers("image_angles_deg");
  if (root.has("ligaments"))
    settings.ligaments = root.texts("ligaments");
  if (root.has("without"))
    settings.without = root.texts("without");
  if (auto axis = root.table("axis"))
    read_axis(*axis, settings.axis);
  if (auto anatomy = root.table("anatomy"))
    read_anatomy(*anatomy, settings.anatomy);
  if (auto motion = root.table("motion"))
    read_motion(*motion, base, settings.motion);
  if (auto ligament = root.table("ligament"))
    read_ligament(*ligament, settings.ligament, settings.given);
  if (auto material = root.table("material"))
    read_material(*material, settings);
  if (auto quasi_static = root.table("static"))
    read_static(*quasi_static, settings.newton);
  if (auto interactive = root.table("interactive"))
    read_interactive(*interactive, settings.interactive);
  if (auto contact = root.table("contact"))
    read_contact(*contact, settings.contact);
  if (auto loads = root.table("loads"))
    read_loads(*loads, settings.free.loads);
  if (auto articular = root.table("articular"))
    read_articular(*articular, settings.free);
  if (auto free = root.table("free"))
    read_free(*free, settings.free);
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
