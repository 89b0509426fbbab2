#pragma once
/// @brief Reading one table of a TOML config into parameters, shared by the one-ligament config
/// (build_config.cpp) and the knee config (knee_config.cpp): typed values with the file, line and
/// key in every error, and unknown keys (typos) refused.

#include "common/error.hpp"
#include "common/toml_table.hpp"
#include "pipeline/stage_graph/build_config.hpp"
#include "pipeline/stage_graph/config_fields.hpp"

#include <toml++/toml.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace ligsim::pipeline {

namespace config_reading {

namespace fs = std::filesystem;

/// Reads typed values of one TOML table (absent: nothing to read) through the project's TOML
/// reader, remembering which keys the config knows, so that unknown keys (typos) are refused.
class Section {
public:
  Section(const toml::table* table, const std::string& name, const fs::path& file)
      : m_file(file)
  {
    if (table)
      m_table.emplace(*table, file.string(), "[" + name + "]");
  }

  template <class T> void read(const std::string& key, T& target)
  {
    if (!has(key)) {
      allow(key);
      return;
    }
    TomlTable& table = *m_table;
    if constexpr (std::is_same_v<T, double>)
      target = table.required_number(key);
    else if constexpr (std::is_same_v<T, int>)
      target = table.integer(key, target);
    else if constexpr (std::is_same_v<T, bool>)
      target = table.boolean(key, target);
    else if constexpr (std::is_same_v<T, std::string>)
      target = table.required_text(key);
    else if constexpr (std::is_same_v<T, std::vector<int>>)
      target = table.integers(key);
    else if constexpr (std::is_same_v<T, std::vector<std::string>>)
      target = table.texts(key);
    else
      target = table.required_vector3(key);
  }

  /// A label: a number or a name, kept as text (as on the command line).
  void read_label(const std::string& key, std::string& target)
  {
    if (m_table)
      target = m_table->label(key, target);
  }

  void read_path(const std::string& key, fs::path& target)
  {
    std::string text;
    read(key, text);
    if (!text.empty())
      target = fs::path(text).is_absolute() ? fs::path(text) : m_file.parent_path() / text;
  }

  /// Marks a sub-table name as known.
  void allow(const std::string& key)
  {
    if (m_table)
      m_table->allow(key);
  }

  bool has(const std::string& key) const { return m_table && m_table->has(key); }

  void reject_unknown() const
  {
    if (m_table)
      m_table->reject_unknown_keys();
  }

private:
  std::optional<TomlTable> m_table;
  fs::path m_file;
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
  static const std::vector<std::string> names = {
      "voxelize", "centerline", "field", "tetmesh", "fibers", "model", "error_estimate", "flexion"};
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

/// Parses a TOML file (none: an empty table) with the command line's `--set`s over it; a syntax
/// error is an InputError with the file and line.
toml::table parse_config_file(const fs::path& file, const std::vector<std::string>& overrides = {});

} // namespace config_reading

} // namespace ligsim::pipeline
