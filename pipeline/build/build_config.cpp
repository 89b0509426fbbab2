#include "pipeline/build/build_config.hpp"

#include "common/error.hpp"

#include <toml++/toml.h>

#include <set>

namespace ligsim::pipeline {

namespace fs = std::filesystem;

namespace {

/// Reads typed values from one TOML table, remembering which keys were used, so that unknown
/// keys (typos) can be reported.
class Section {
public:
  Section(const toml::table* table, std::string name, fs::path file)
    : m_table(table), m_name(std::move(name)), m_file(std::move(file))
  {
  }

  template <class T>
  void read(const std::string& key, T& target)
  {
    m_known.insert(key);
    if (m_table == nullptr)
      return;
    const toml::node* node = m_table->get(key);
    if (node == nullptr)
      return;
    if constexpr (std::is_same_v<T, double>) {
      if (auto v = node->value<double>()) { // accepts integers too
        target = *v;
        return;
      }
    } else if constexpr (std::is_same_v<T, int>) {
      if (auto v = node->value<int64_t>()) {
        target = static_cast<int>(*v);
        return;
      }
    } else if constexpr (std::is_same_v<T, bool>) {
      if (auto v = node->value<bool>()) {
        target = *v;
        return;
      }
    } else if constexpr (std::is_same_v<T, std::string>) {
      if (auto v = node->value<std::string>()) {
        target = *v;
        return;
      }
    } else if constexpr (std::is_same_v<T, std::vector<int>>) {
      if (const toml::array* array = node->as_array()) {
        target.clear();
        for (const toml::node& item : *array) {
          const auto v = item.value<int64_t>();
          if (!v)
            type_error(key, node, "a list of integers");
          target.push_back(static_cast<int>(*v));
        }
        return;
      }
    } else if constexpr (std::is_same_v<T, Eigen::Vector3d>) {
      if (const toml::array* array = node->as_array(); array && array->size() == 3) {
        for (std::size_t i = 0; i < 3; ++i) {
          const auto v = (*array)[i].value<double>();
          if (!v)
            type_error(key, node, "three numbers");
          target[static_cast<Eigen::Index>(i)] = *v;
        }
        return;
      }
    }
    type_error(key, node, expected_name<T>());
  }

  void read_path(const std::string& key, fs::path& target)
  {
    std::string text;
    read(key, text);
    if (!text.empty())
      target = fs::path(text).is_absolute() ? fs::path(text) : m_file.parent_path() / text;
  }

  /// Marks a sub-table name as known.
  void allow(const std::string& key) { m_known.insert(key); }

  bool has(const std::string& key) const { return m_table && m_table->contains(key); }

  void reject_unknown() const
  {
    if (m_table == nullptr)
      return;
    for (const auto& [key, node] : *m_table)
      if (!m_known.count(std::string(key.str())))
        fail("{}:{}: unknown key '{}' in [{}]", m_file.string(), node.source().begin.line,
             key.str(), m_name);
  }

private:
  template <class T>
  static const char* expected_name()
  {
    if constexpr (std::is_same_v<T, double>)
      return "a number";
    else if constexpr (std::is_same_v<T, int>)
      return "an integer";
    else if constexpr (std::is_same_v<T, bool>)
      return "true or false";
    else if constexpr (std::is_same_v<T, std::string>)
      return "a string";
    else if constexpr (std::is_same_v<T, std::vector<int>>)
      return "a list of integers";
    else
      return "three numbers";
  }

  [[noreturn]] void type_error(const std::string& key, const toml::node* node, const char* expected) const
  {
    fail("{}:{}: [{}] {} must be {}", m_file.string(), node->source().begin.line, m_name, key,
         expected);
  }

  const toml::table* m_table;
  std::string m_name;
  fs::path m_file;
  std::set<std::string> m_known;
};

void read_rule(Section&& section, attachments::Rule& rule)
{
  section.read("rule", rule.rule);
  section.read("indices", rule.indices);
  section.read("array", rule.array);
  section.read("distance_mm", rule.distance_mm);
  section.read("end_length_mm", rule.end_length_mm);
  section.read("end", rule.end);
  section.reject_unknown();
}

const toml::table* table_at(const toml::table* parent, const char* key)
{
  return parent ? parent->get_as<toml::table>(key) : nullptr;
}

} // namespace

BuildConfig load_build_config(const fs::path& file)
{
  if (!fs::is_regular_file(file))
    fail("missing config file '{}'", file.string());
  toml::table root;
  try {
    root = toml::parse_file(file.string());
  } catch (const toml::parse_error& e) {
    fail("{}:{}: {}", file.string(), e.source().begin.line, e.description());
  }

  BuildConfig config;
  Section top(&root, "top level", file);
  for (const char* name : {"input", "attachments", "voxelize", "centerline", "field", "tetmesh",
                           "fibers", "model", "material", "flexion"})
    top.allow(name);
  top.reject_unknown();

  Section input(table_at(&root, "input"), "input", file);
  input.read_path("surface", config.surface);
  input.read_path("femur", config.femur);
  input.read_path("tibia", config.tibia);
  input.reject_unknown();

  const toml::table* attachments = table_at(&root, "attachments");
  Section attachment_section(attachments, "attachments", file);
  attachment_section.allow("femur");
  attachment_section.allow("tibia");
  attachment_section.reject_unknown();
  read_rule(Section(table_at(attachments, "femur"), "attachments.femur", file), config.femur_attachment);
  read_rule(Section(table_at(attachments, "tibia"), "attachments.tibia", file), config.tibia_attachment);

  Section voxelize(table_at(&root, "voxelize"), "voxelize", file);
  voxelize.read("spacing_mm", config.voxelize.spacing_mm);
  voxelize.read("padding_voxels", config.voxelize.padding_voxels);
  voxelize.read("max_voxels", config.voxelize.max_voxels);
  voxelize.reject_unknown();

  Section centerline(table_at(&root, "centerline"), "centerline", file);
  centerline.read("alpha", config.centerline.alpha);
  std::string span = centerline::to_string(config.centerline.span);
  centerline.read("span", span);
  config.centerline.span = centerline::parse_span(span);
  centerline.read("refine", config.centerline.refine);
  centerline.read("relax_iterations", config.centerline.relax_iterations);
  centerline.read("extend_to_surface", config.centerline.extend_to_surface);
  centerline.read("point_spacing_mm", config.centerline.point_spacing_mm);
  centerline.read("smoothing_passes", config.centerline.smoothing_passes);
  centerline.reject_unknown();

  Section field(table_at(&root, "field"), "field", file);
  std::string method = field::to_string(config.field.method);
  field.read("method", method);
  config.field.method = field::parse_method(method);
  field.read("laplace_tolerance", config.field.laplace_tolerance);
  field.read("laplace_max_iterations", config.field.laplace_max_iterations);
  field.reject_unknown();

  Section tetmesh(table_at(&root, "tetmesh"), "tetmesh", file);
  tetmesh.read("cell_size_mm", config.tetmesh.cell_size_mm);
  tetmesh.read("facet_size_mm", config.tetmesh.facet_size_mm);
  tetmesh.read("facet_distance_mm", config.tetmesh.facet_distance_mm);
  tetmesh.read("facet_angle_deg", config.tetmesh.facet_angle_deg);
  tetmesh.read("radius_edge_ratio", config.tetmesh.radius_edge_ratio);
  tetmesh.read("exude_slivers", config.tetmesh.exude_slivers);
  tetmesh.read("perturb", config.tetmesh.perturb);
  tetmesh.read("seed", config.tetmesh.seed);
  tetmesh.reject_unknown();

  Section fibers(table_at(&root, "fibers"), "fibers", file);
  fibers.read("samples_per_tet", config.fibers.samples_per_tet);
  fibers.reject_unknown();

  Section model(table_at(&root, "model"), "model", file);
  model.read("in_situ_strain", config.model.in_situ_strain);
  model.reject_unknown();

  Section material(table_at(&root, "material"), "material", file);
  material.read("mu_mpa", config.material.mu_mpa);
  material.read("c3_mpa", config.material.c3_mpa);
  material.read("c4", config.material.c4);
  material.read("c5_mpa", config.material.c5_mpa);
  material.read("lambda_star", config.material.lambda_star);
  material.read("bulk_modulus_mpa", config.material.bulk_modulus_mpa);
  material.read("fiber_convention", config.material.fiber_convention);
  material.read("volumetric", config.material.volumetric);
  material.reject_unknown();

  Section flexion(table_at(&root, "flexion"), "flexion", file);
  flexion.read("max_angle_deg", config.flexion.max_angle_deg);
  flexion.read("steps", config.flexion.steps);
  config.flexion.axis_given = flexion.has("axis_point_mm") || flexion.has("axis_direction");
  flexion.read("axis_point_mm", config.flexion.axis_point_mm);
  flexion.read("axis_direction", config.flexion.axis_direction);
  flexion.reject_unknown();
  return config;
}

namespace {

nlohmann::json rule_json(const attachments::Rule& rule)
{
  return {{"rule", rule.rule},           {"indices", rule.indices},
          {"array", rule.array},         {"distance_mm", rule.distance_mm},
          {"end_length_mm", rule.end_length_mm}, {"end", rule.end}};
}

std::string path_text(const fs::path& path) { return path.empty() ? "" : path.string(); }

} // namespace

nlohmann::json stage_parameters(const BuildConfig& c, const std::string& stage)
{
  if (stage == "attachments")
    return {{"femur", rule_json(c.femur_attachment)}, {"tibia", rule_json(c.tibia_attachment)}};
  if (stage == "distance")
    return nlohmann::json::object(); // exact distances: nothing to choose
  if (stage == "voxelize")
    return {{"spacing_mm", c.voxelize.spacing_mm},
            {"padding_voxels", c.voxelize.padding_voxels},
            {"max_voxels", c.voxelize.max_voxels}};
  if (stage == "centerline")
    return {{"alpha", c.centerline.alpha},
            {"span", centerline::to_string(c.centerline.span)},
            {"refine", c.centerline.refine},
            {"relax_iterations", c.centerline.relax_iterations},
            {"extend_to_surface", c.centerline.extend_to_surface},
            {"point_spacing_mm", c.centerline.point_spacing_mm},
            {"smoothing_passes", c.centerline.smoothing_passes}};
  if (stage == "field")
    return {{"method", field::to_string(c.field.method)},
            {"laplace_tolerance", c.field.laplace_tolerance},
            {"laplace_max_iterations", c.field.laplace_max_iterations}};
  if (stage == "tetmesh")
    return {{"cell_size_mm", c.tetmesh.cell_size_mm},
            {"facet_size_mm", c.tetmesh.facet_size_mm},
            {"facet_distance_mm", c.tetmesh.facet_distance_mm},
            {"facet_angle_deg", c.tetmesh.facet_angle_deg},
            {"radius_edge_ratio", c.tetmesh.radius_edge_ratio},
            {"exude_slivers", c.tetmesh.exude_slivers},
            {"perturb", c.tetmesh.perturb},
            {"seed", c.tetmesh.seed}};
  if (stage == "fibers")
    return {{"samples_per_tet", c.fibers.samples_per_tet}};
  if (stage == "model")
    return {{"in_situ_strain", c.model.in_situ_strain},
            {"material",
             {{"mu_mpa", c.material.mu_mpa},
              {"c3_mpa", c.material.c3_mpa},
              {"c4", c.material.c4},
              {"c5_mpa", c.material.c5_mpa},
              {"lambda_star", c.material.lambda_star},
              {"bulk_modulus_mpa", c.material.bulk_modulus_mpa},
              {"fiber_convention", c.material.fiber_convention},
              {"volumetric", c.material.volumetric}}},
            {"flexion",
             {{"max_angle_deg", c.flexion.max_angle_deg},
              {"steps", c.flexion.steps},
              {"axis_given", c.flexion.axis_given},
              {"axis_point_mm", {c.flexion.axis_point_mm.x(), c.flexion.axis_point_mm.y(), c.flexion.axis_point_mm.z()}},
              {"axis_direction", {c.flexion.axis_direction.x(), c.flexion.axis_direction.y(), c.flexion.axis_direction.z()}}}}};
  fail("unknown stage '{}'", stage);
}

nlohmann::json to_json(const BuildConfig& c)
{
  nlohmann::json all = {{"surface", path_text(c.surface)},
                        {"femur", path_text(c.femur)},
                        {"tibia", path_text(c.tibia)}};
  for (const char* stage : {"attachments", "voxelize", "distance", "centerline", "field", "tetmesh", "fibers", "model"})
    all[stage] = stage_parameters(c, stage);
  return all;
}

} // namespace ligsim::pipeline
