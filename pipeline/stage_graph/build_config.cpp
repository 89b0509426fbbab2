#include "pipeline/stage_graph/build_config.hpp"

#include "common/error.hpp"
#include "common/toml_numbers.hpp"
#include "pipeline/stage_graph/config_fields.hpp"

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
      : m_table(table)
      , m_name(std::move(name))
      , m_file(std::move(file))
  {
  }

  template <class T> void read(const std::string& key, T& target)
  {
    m_known.insert(key);
    if (m_table == nullptr)
      return;
    const toml::node* node = m_table->get(key);
    if (node == nullptr)
      return;
    if constexpr (std::is_same_v<T, double>) {
      if (auto v = toml_number(*node)) {
        target = *v;
        return;
      }
    } else if constexpr (std::is_same_v<T, int>) {
      if (auto v = toml_int(*node)) {
        target = *v;
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
          const auto v = toml_int(item);
          if (!v)
            type_error(key, node, "a list of integers");
          target.push_back(*v);
        }
        return;
      }
    } else if constexpr (std::is_same_v<T, Eigen::Vector3d>) {
      if (const toml::array* array = node->as_array(); array && array->size() == 3) {
        for (std::size_t i = 0; i < 3; ++i) {
          const auto v = toml_number(*array->get(i));
          if (!v)
            type_error(key, node, "three numbers");
          target[static_cast<Eigen::Index>(i)] = *v;
        }
        return;
      }
    }
    type_error(key, node, expected_name<T>());
  }

  /// A label: a number or a name, kept as text (as on the command line).
  void read_label(const std::string& key, std::string& target)
  {
    m_known.insert(key);
    const toml::node* node = m_table ? m_table->get(key) : nullptr;
    if (node == nullptr)
      return;
    if (auto number = node->value<int64_t>())
      target = std::to_string(*number);
    else if (auto name = node->value<std::string>())
      target = *name;
    else
      type_error(key, node, "a label number or name");
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
  template <class T> static const char* expected_name()
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

  [[noreturn]] void type_error(const std::string& key, const toml::node* node,
                               const char* expected) const
  {
    fail("{}:{}: [{}] {} must be {}", m_file.string(), node->source().begin.line, m_name, key,
         expected);
  }

  const toml::table* m_table;
  std::string m_name;
  fs::path m_file;
  std::set<std::string> m_known;
};

/// Reads each visited parameter from one section.
struct TomlReader {
  Section& section;

  template <class T> void operator()(const char* key, T& value) { section.read(key, value); }

  template <class E> void operator()(const char* key, Choice<E> choice)
  {
    std::string text = choice.name(choice.value);
    section.read(key, text);
    choice.value = choice.parse(text);
  }
};

/// Reads the table `name` of `parent` with `visit_fields` and rejects keys it does not know.
template <class P, class VisitFields>
void read_section(const toml::table* parent, const char* name, const std::string& label,
                  const fs::path& file, P& parameters, VisitFields visit_fields)
{
  Section section(parent ? parent->get_as<toml::table>(name) : nullptr, label, file);
  visit_fields(parameters, TomlReader{section});
  section.reject_unknown();
}

const toml::table* table_at(const toml::table* parent, const char* key)
{
  return parent ? parent->get_as<toml::table>(key) : nullptr;
}

/// A path of the config, relative to the config's folder unless absolute ("" stays "").
std::string relative_to(const fs::path& config_file, const std::string& text)
{
  if (text.empty() || fs::path(text).is_absolute())
    return text;
  return (config_file.parent_path() / text).string();
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
  for (const char* name : {"input", "anatomy", "attachments", "voxelize", "centerline", "field",
                           "tetmesh", "fibers", "model", "material", "flexion"})
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

  read_section(&root, "anatomy", "anatomy", file, config.anatomy,
               [](auto& p, auto&& v) { visit_anatomy(p, v); });
  if (!config.anatomy.side.empty() && config.anatomy.side != "left" &&
      config.anatomy.side != "right")
    fail("{}: [anatomy] side must be \"left\" or \"right\", got \"{}\"", file.string(),
         config.anatomy.side);
  for (std::string* surface :
       {&config.anatomy.medial_epicondyle_surface, &config.anatomy.lateral_epicondyle_surface})
    *surface = relative_to(file, *surface);

  const toml::table* attachments = table_at(&root, "attachments");
  Section attachment_section(attachments, "attachments", file);
  attachment_section.allow("femur");
  attachment_section.allow("tibia");
  attachment_section.reject_unknown();
  const auto rule = [](auto& r, auto&& visit) { visit_rule(r, visit); };
  read_section(attachments, "femur", "attachments.femur", file, config.femur_attachment, rule);
  read_section(attachments, "tibia", "attachments.tibia", file, config.tibia_attachment, rule);
  for (attachments::Rule* r : {&config.femur_attachment, &config.tibia_attachment})
    r->patch = relative_to(file, r->patch);

  read_section(&root, "voxelize", "voxelize", file, config.voxelize,
               [](auto& p, auto&& v) { visit_voxelize(p, v); });
  read_section(&root, "centerline", "centerline", file, config.centerline,
               [](auto& p, auto&& v) { visit_centerline(p, v); });
  read_section(&root, "field", "field", file, config.field,
               [](auto& p, auto&& v) { visit_field(p, v); });
  read_section(&root, "tetmesh", "tetmesh", file, config.tetmesh,
               [](auto& p, auto&& v) { visit_tetmesh(p, v); });
  read_section(&root, "fibers", "fibers", file, config.fibers,
               [](auto& p, auto&& v) { visit_fibers(p, v); });
  read_section(&root, "model", "model", file, config.model,
               [](auto& p, auto&& v) { visit_model(p, v); });
  read_section(&root, "material", "material", file, config.material,
               [](auto& p, auto&& v) { visit_material(p, v); });
  read_section(&root, "flexion", "flexion", file, config.flexion,
               [](auto& p, auto&& v) { visit_flexion(p, v); });
  if (const toml::table* flexion = table_at(&root, "flexion"))
    config.flexion.axis_given =
        flexion->contains("axis_point_mm") || flexion->contains("axis_direction");
  return config;
}

namespace {

/// Writes each visited parameter as a JSON member.
struct JsonWriter {
  nlohmann::json& json;

  template <class T> void operator()(const char* key, const T& value) { json[key] = value; }

  void operator()(const char* key, const Eigen::Vector3d& value)
  {
    json[key] = {value.x(), value.y(), value.z()};
  }

  template <class E> void operator()(const char* key, Choice<E> choice)
  {
    json[key] = choice.name(choice.value);
  }
};

template <class P, class VisitFields>
nlohmann::json as_json(const P& parameters, VisitFields visit_fields)
{
  nlohmann::json json = nlohmann::json::object();
  visit_fields(parameters, JsonWriter{json});
  return json;
}

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
    anatomy["label_map_frame"] = !c.labels.empty();
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
    model["material"] = as_json(c.material, [](auto& p, auto&& v) { visit_material(p, v); });
    model["flexion"] = as_json(c.flexion, [](auto& p, auto&& v) { visit_flexion(p, v); });
    model["flexion"]["axis_given"] = c.flexion.axis_given;
    return model;
  }
  fail("unknown stage '{}'", stage);
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
  return all;
}

} // namespace ligsim::pipeline
