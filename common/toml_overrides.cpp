#include "common/toml_overrides.hpp"

#include "common/error.hpp"

#include <fmt/format.h>

#include <optional>

namespace ligsim {

namespace {

/// "a.b.key = VALUE" parsed as TOML under the name "--set a.b.key=VALUE"; nullopt when VALUE is
/// not TOML.
std::optional<toml::table> parse_as_toml(const std::string& key, const std::string& value,
                                         const std::string& name)
{
  try {
    return toml::parse(key + " = " + value, name);
  } catch (const toml::parse_error&) {
    return std::nullopt;
  }
}

/// A bare word as a TOML string.
std::string quoted(const std::string& word)
{
  std::string text = "\"";
  for (const char c : word) {
    if (c == '"' || c == '\\')
      text += '\\';
    text += c;
  }
  return text + "\"";
}

/// A double as a TOML float: the shortest text that reads back as the same double, with a
/// fraction where it would otherwise read as an integer.
std::string toml_float(double value)
{
  std::string text = fmt::format("{}", value);
  if (text.find_first_of(".eEni") == std::string::npos)
    text += ".0";
  return text;
}

template <class T, class Format>
std::string toml_array(const std::vector<T>& values, Format&& format)
{
  std::string text = "[";
  for (std::size_t i = 0; i < values.size(); ++i)
    text += (i > 0 ? ", " : "") + format(values[i]);
  return text + "]";
}

std::string toml_integer(int value)
{
  return std::to_string(value);
}

/// The assignment as a table of one dotted key: TOML first, a quoted word second.
toml::table parse_assignment(const std::string& assignment)
{
  const std::string name = "--set " + assignment;
  const std::size_t equals = assignment.find('=');
  const std::string key = assignment.substr(0, equals);
  const bool malformed = equals == std::string::npos || key.empty() ||
                         key.find_first_of("[]\n\"' \t") != std::string::npos ||
                         key.front() == '.' || key.back() == '.' ||
                         key.find("..") != std::string::npos;
  if (malformed)
    fail("{}: expected TABLE.KEY=VALUE, e.g. --set tetmesh.cell_size_mm=1.2", name);
  const std::string value = assignment.substr(equals + 1);
  if (auto table = parse_as_toml(key, value, name))
    return std::move(*table);
  if (!value.empty() && value.find('"') == std::string::npos)
    if (auto table = parse_as_toml(key, quoted(value), name))
      return std::move(*table);
  fail("{}: the value is not TOML (a number, true or false, \"text\" or [a list])", name);
}

/// The sub-table of `table` at `path` (which the assignment's parse made).
toml::table& descend(toml::table& table, const std::vector<std::string>& path)
{
  toml::table* at = &table;
  for (const std::string& part : path)
    at = at->get_as<toml::table>(part);
  return *at;
}

/// Merges `from` (at `path` within the assignment's table) into `into`: tables key by key,
/// arrays of tables element by element, values replaced. Nodes are moved, keeping their
/// source ("--set ..."), which the readers' messages name.
void merge(toml::table& into, toml::table& from, const std::string& assignment,
           std::vector<std::string>& path)
{
  for (auto&& [key, node] : from) {
    const std::string name(key.str());
    toml::node* existing = into.get(name);
    path.push_back(name);
    if (existing && existing->is_table() && node.is_table()) {
      merge(*existing->as_table(), *node.as_table(), assignment, path);
    } else if (existing && existing->is_array_of_tables() && node.is_table()) {
      for (toml::node& element : *existing->as_array()) {
        // A fresh parse for each element: copied nodes would lose their source.
        toml::table again = parse_assignment(assignment);
        std::vector<std::string> inner = path;
        merge(*element.as_table(), descend(again, path), assignment, inner);
      }
    } else {
      into.insert_or_assign(name, std::move(node));
    }
    path.pop_back();
  }
}

} // namespace

std::string toml_assignment(const std::string& key, double value)
{
  return key + "=" + toml_float(value);
}

std::string toml_assignment(const std::string& key, int value)
{
  return key + "=" + toml_integer(value);
}

std::string toml_assignment(const std::string& key, bool value)
{
  return key + "=" + (value ? "true" : "false");
}

std::string toml_assignment(const std::string& key, const std::string& text)
{
  return key + "=" + quoted(text);
}

std::string toml_assignment(const std::string& key, const std::vector<double>& values)
{
  return key + "=" + toml_array(values, toml_float);
}

std::string toml_assignment(const std::string& key, const std::vector<int>& values)
{
  return key + "=" + toml_array(values, toml_integer);
}

std::string toml_assignment(const std::string& key, const std::vector<std::string>& values)
{
  return key + "=" + toml_array(values, quoted);
}

void apply_overrides(toml::table& root, const std::vector<std::string>& assignments)
{
  for (const std::string& assignment : assignments) {
    toml::table table = parse_assignment(assignment);
    std::vector<std::string> path;
    merge(root, table, assignment, path);
  }
}

} // namespace ligsim
