#pragma once
/// @brief Typed reading of one TOML table with errors that name the file, table and key, and
/// a check that no unknown (mistyped) key was left unread.

#include <Eigen/Core>
#include <toml++/toml.h>

#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace ligsim::sim {

/// Parses TOML text; a syntax error is an InputError "name: line N: problem".
toml::table parse_toml(const std::string& text, const std::string& name);

/// The whole text of `file`; InputError "cannot open <what> <file>" when it cannot be read.
std::string read_text_file(const std::filesystem::path& file, const std::string& what);

class TomlTable {
public:
  /// `where` names the table in messages, e.g. "scene.toml [solver]".
  TomlTable(const toml::table& table, std::string where);

  bool has(const std::string& key) const;
  const std::string& where() const { return m_where; }

  double number(const std::string& key, double fallback);
  double required_number(const std::string& key);
  int integer(const std::string& key, int fallback);
  bool boolean(const std::string& key, bool fallback);
  std::string text(const std::string& key, const std::string& fallback);
  std::string required_text(const std::string& key);
  Eigen::Vector3d vector3(const std::string& key, const Eigen::Vector3d& fallback);
  Eigen::Vector3d required_vector3(const std::string& key);
  Eigen::Vector3i integer_vector3(const std::string& key);
  std::vector<int> integers(const std::string& key);
  /// An array of strings.
  std::vector<std::string> texts(const std::string& key);
  /// An array of numbers (integers or floats).
  std::vector<double> numbers(const std::string& key);
  /// A sub-table (inline or not); nullopt when absent.
  std::optional<TomlTable> table(const std::string& key);
  /// An array of tables ([[key]]); empty when absent.
  std::vector<TomlTable> tables(const std::string& key);
  /// Keys of this table, in file order.
  std::vector<std::string> keys() const;

  /// Throws InputError for the first key that nothing read.
  void reject_unknown_keys() const;

  [[noreturn]] void fail_at(const std::string& key, const std::string& problem) const;

private:
  const toml::node& node(const std::string& key);

  const toml::table* m_table;
  std::string m_where;
  std::set<std::string> m_read;
};

} // namespace ligsim::sim
