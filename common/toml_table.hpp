#pragma once
/// @brief Typed reading of one TOML table, the one reader of every TOML file of the project
/// (build and knee configs, flexion configs, scenes, membrane scenes): errors name the file, line,
/// table and key ("knee.toml:12: [tetmesh] cell_size_mm: expected a number"), and keys that
/// nothing read (typos) are refused.

#include <Eigen/Core>
#include <toml++/toml.h>

#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace ligsim {

/// Parses TOML text; a syntax error is an InputError "name: line N: problem".
toml::table parse_toml(const std::string& text, const std::string& name);

/// The whole text of `file`; InputError "cannot open <what> <file>" when it cannot be read.
std::string read_text_file(const std::filesystem::path& file, const std::string& what);

class TomlTable {
public:
  /// `file` names the file in messages; `label` the table ("[solver]"; empty: the top level).
  TomlTable(const toml::table& table, std::string file, std::string label = "");

  bool has(const std::string& key) const;
  /// "scene.toml [solver]": the file and table, for messages about the table as a whole.
  const std::string& where() const { return m_where; }

  double number(const std::string& key, double fallback);
  double required_number(const std::string& key);
  int integer(const std::string& key, int fallback);
  bool boolean(const std::string& key, bool fallback);
  std::string text(const std::string& key, const std::string& fallback);
  std::string required_text(const std::string& key);
  /// A label number or name, kept as text (as on the command line).
  std::string label(const std::string& key, const std::string& fallback);
  Eigen::Vector3d vector3(const std::string& key, const Eigen::Vector3d& fallback);
  Eigen::Vector3d required_vector3(const std::string& key);
  Eigen::Vector3i integer_vector3(const std::string& key);
  std::vector<int> integers(const std::string& key);
  /// An array of strings.
  std::vector<std::string> texts(const std::string& key);
  /// An array of numbers (integers or floats).
  std::vector<double> numbers(const std::string& key);
  /// An array of arrays of numbers, e.g. a list of points.
  std::vector<std::vector<double>> number_lists(const std::string& key);
  /// A sub-table (inline or not), named "<where> [key]" in messages; nullopt when absent.
  std::optional<TomlTable> table(const std::string& key);
  /// A sub-table that must be there.
  TomlTable required_table(const std::string& key);
  /// An array of tables ([[key]]); empty when absent.
  std::vector<TomlTable> tables(const std::string& key);
  /// Keys of this table, in file order.
  std::vector<std::string> keys() const;

  /// Marks a key as known that another reader takes (a sub-table).
  void allow(const std::string& key) { m_read.insert(key); }
  /// Throws InputError "FILE:LINE: unknown key 'k' in [table]" for the first key nothing read.
  void reject_unknown_keys() const;
  /// Throws InputError for the first key outside `allowed`, before any value is read: a
  /// mistyped required key is then named as the typo it is, not as a missing key.
  void only(const std::vector<std::string_view>& allowed) const;

  /// InputError "FILE:LINE: [table] key: problem" (the key's line where it is in the file).
  [[noreturn]] void fail_at(const std::string& key, const std::string& problem) const;

private:
  const toml::node& node(const std::string& key);
  /// "FILE:LINE" of the key, or "FILE" where it is absent.
  std::string location(const std::string& key) const;
  /// The label of a sub-table `key` ("[a.key]") or of entry `index` of an array of tables.
  std::string child_label(const std::string& key, std::optional<std::size_t> index = {}) const;

  const toml::table* m_table;
  std::string m_file;
  std::string m_label;
  std::string m_where;
  std::set<std::string> m_read;
};

} // namespace ligsim
