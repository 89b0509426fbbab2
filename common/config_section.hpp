#pragma once
/// @brief Reading one table of a TOML config into parameters, for every config of the project
/// (build and knee configs, flexion configs, scenes and tear scenes): typed values with the file,
/// line and key in every error, and unknown keys (typos) refused. A config's parameter list (its
/// visit_* functions) is read with `read_fields`, so that the list is the one place that names a
/// key.

#include "common/config_choice.hpp"
#include "common/config_field_kinds.hpp"
#include "common/error.hpp"
#include "common/toml_table.hpp"

#include <toml++/toml.h>

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace ligsim {

/// Reads typed values of one TOML table (absent: nothing to read) through the project's TOML
/// reader, remembering which keys the config knows, so that unknown keys (typos) are refused.
class ConfigSection {
public:
  /// `name` labels the table in messages ("[name]"); `file` names the file, and relative paths
  /// are read from its folder.
  ConfigSection(const toml::table* table, const std::string& name,
                const std::filesystem::path& file)
      : m_file(file)
  {
    if (table)
      m_table = &m_owned.emplace(*table, file.string(), "[" + name + "]");
  }
  /// Over a table a reader already holds (the keys read here count as read there).
  explicit ConfigSection(TomlTable& table)
      : m_table(&table)
  {
  }
  ConfigSection(const ConfigSection&) = delete;
  ConfigSection& operator=(const ConfigSection&) = delete;

  /// Reads `key` over `target` where the table has it; a key it lacks keeps its value.
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
    else if constexpr (std::is_same_v<T, std::optional<bool>>)
      target = table.boolean(key, false);
    else if constexpr (std::is_same_v<T, std::string>)
      target = table.required_text(key);
    else if constexpr (std::is_same_v<T, std::vector<int>>)
      target = table.integers(key);
    else if constexpr (std::is_same_v<T, std::vector<double>>)
      target = table.numbers(key);
    else if constexpr (std::is_same_v<T, std::vector<std::string>>)
      target = table.texts(key);
    else
      target = table.required_vector3(key);
  }

  /// An enumerated value: one of the choice's names, else an error at the key naming them.
  template <class E> void read(const std::string& key, Choice<E> choice)
  {
    if (!has(key)) {
      allow(key);
      return;
    }
    const std::string text = m_table->required_text(key);
    const auto value = choice.parse(text);
    if (!value)
      fail_at(key, "expected " + choice.expected() + ", got \"" + text + "\"");
    choice.value = *value;
  }

  /// A parameter the config must give: "missing" at the table where it lacks it.
  template <class T> void read(const std::string& key, Required<T> required)
  {
    if (!has(key))
      fail_at(key, "missing");
    read(key, required.value);
  }

  /// An angle given in degrees, held in radians.
  template <class D> void read(const std::string& key, Degrees<D> angle)
  {
    if (!has(key)) {
      allow(key);
      return;
    }
    double degrees = 0.0;
    read(key, degrees);
    angle.radians = Degrees<D>::to_radians(degrees);
  }

  /// A label: a number or a name, kept as text (as on the command line).
  void read_label(const std::string& key, std::string& target)
  {
    if (m_table)
      target = m_table->label(key, target);
  }

  /// A path, relative to the config file's folder unless absolute.
  void read_path(const std::string& key, std::filesystem::path& target)
  {
    std::string text;
    read(key, text);
    if (!text.empty())
      target = std::filesystem::path(text).is_absolute() ? std::filesystem::path(text)
                                                         : m_file.parent_path() / text;
  }

  /// Marks a key as known that another reader takes (a sub-table).
  void allow(const std::string& key)
  {
    if (m_table)
      m_table->allow(key);
  }

  bool has(const std::string& key) const { return m_table && m_table->has(key); }
  /// "FILE [table]", for messages about the table as a whole.
  std::string where() const { return m_table ? m_table->where() : m_file.string(); }

  /// The table itself, for a reader of its own (none where the config lacks it).
  TomlTable* table() { return m_table; }

  void reject_unknown() const
  {
    if (m_table)
      m_table->reject_unknown_keys();
  }

  /// InputError "FILE:LINE: [table] key: problem".
  [[noreturn]] void fail_at(const std::string& key, const std::string& problem) const
  {
    if (m_table)
      m_table->fail_at(key, problem);
    throw InputError(m_file.string() + ": " + key + ": " + problem);
  }

private:
  std::optional<TomlTable> m_owned;
  TomlTable* m_table = nullptr;
  std::filesystem::path m_file;
};

/// Reads each visited parameter from one section: `visit_fields(parameters, FieldReader{s})`.
struct FieldReader {
  ConfigSection& section;

  template <class T> void operator()(const char* key, T& value) { section.read(key, value); }
  template <class E> void operator()(const char* key, Choice<E> choice)
  {
    section.read(key, std::move(choice));
  }
  template <class T> void operator()(const char* key, Required<T> required)
  {
    section.read(key, required);
  }
  template <class D> void operator()(const char* key, Degrees<D> angle)
  {
    section.read(key, angle);
  }
};

/// Lists the keys a parameter list names, in its order: `visit_fields(parameters,
/// FieldNames{keys})`.
struct FieldNames {
  std::vector<std::string_view>& keys;

  template <class T> void operator()(const char* key, const T&) { keys.emplace_back(key); }
};

/// Reads the table `name` of `parent` (absent: nothing) with `visit_fields`; rejects keys it does
/// not know.
template <class P, class VisitFields>
void read_fields(const toml::table* parent, const char* name, const std::string& label,
                 const std::filesystem::path& file, P& parameters, VisitFields visit_fields)
{
  ConfigSection section(parent ? parent->get_as<toml::table>(name) : nullptr, label, file);
  visit_fields(parameters, FieldReader{section});
  section.reject_unknown();
}

} // namespace ligsim
