#pragma once
/// @brief Reading one table of a TOML config into parameters, shared by the one-ligament config
/// (build_config.cpp) and the knee config (knee_config.cpp): typed values with the file, line and
/// key in every error, and unknown keys (typos) refused.

#include "common/error.hpp"
#include "common/toml_numbers.hpp"
#include "pipeline/stage_graph/build_config.hpp"
#include "pipeline/stage_graph/config_fields.hpp"

#include <toml++/toml.h>

#include <filesystem>
#include <set>
#include <string>
#include <vector>

namespace ligsim::pipeline {

namespace config_reading {

namespace fs = std::filesystem;

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
    } else if constexpr (std::is_same_v<T, std::vector<std::string>>) {
      if (const toml::array* array = node->as_array()) {
        target.clear();
        for (const toml::node& item : *array) {
          const auto v = item.value<std::string>();
          if (!v)
            type_error(key, node, "a list of strings");
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
    else if constexpr (std::is_same_v<T, std::vector<std::string>>)
      return "a list of strings";
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

inline const toml::table* table_at(const toml::table* parent, const char* key)
{
  return parent ? parent->get_as<toml::table>(key) : nullptr;
}

/// A path of the config, relative to the config's folder unless absolute ("" stays "").
inline std::string relative_to(const fs::path& config_file, const std::string& text)
{
  if (text.empty() || fs::path(text).is_absolute())
    return text;
  return (config_file.parent_path() / text).string();
}

/// The stage sections a config table may carry, in data-flow order (besides [input], [anatomy],
/// [attachments] and [material]).
inline const std::vector<std::string>& stage_section_names()
{
  static const std::vector<std::string> names = {"voxelize", "centerline", "field",  "tetmesh",
                                                 "fibers",   "model",      "flexion"};
  return names;
}

/// Reads the stage sections of `table` over `config` (keys it lacks keep their value); `prefix`
/// goes before the section names in errors ("" or "ligament.").
void read_stage_sections(const toml::table& table, const std::string& prefix, const fs::path& file,
                         BuildConfig& config);

/// Reads [anatomy] of `table` over `config`, landmark surfaces resolved against the file.
void read_anatomy_section(const toml::table& table, const fs::path& file, BuildConfig& config);

/// Reads [<prefix>attachments] of `table` over `config`: `femur`, and the ligament's distal
/// footprint under one of `distal_bones` (into config.tibia_attachment). Returns the distal bone
/// named (the first of `distal_bones` when the table names none). Throws InputError when more
/// than one is given.
std::string read_attachment_sections(const toml::table& table, const std::string& prefix,
                                     const fs::path& file,
                                     const std::vector<std::string>& distal_bones,
                                     BuildConfig& config);

/// Reads [<prefix>material] of `table` over `config`.
void read_material_section(const toml::table& table, const std::string& prefix,
                           const fs::path& file, BuildConfig& config);

/// Parses a TOML file; a syntax error is an InputError with the file and line.
toml::table parse_config_file(const fs::path& file);

} // namespace config_reading

} // namespace ligsim::pipeline
