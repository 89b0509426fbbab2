#include "common/toml_table.hpp"

#include "common/error.hpp"
#include "common/toml_numbers.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <sstream>

namespace ligsim {

toml::table parse_toml(const std::string& text, const std::string& name)
{
  try {
    return toml::parse(text, name);
  } catch (const toml::parse_error& e) {
    fail("{}: line {}: {}", name, e.source().begin.line, e.description());
  }
}

std::string read_text_file(const std::filesystem::path& file, const std::string& what)
{
  std::ifstream in(file);
  if (!in)
    fail("cannot open {} {}", what, file.string());
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TomlTable::TomlTable(const toml::table& table, std::string file, std::string label)
    : m_table(&table)
    , m_file(std::move(file))
    , m_label(std::move(label))
    , m_where(m_label.empty() ? m_file : m_file + " " + m_label)
{
}

bool TomlTable::has(const std::string& key) const
{
  return m_table->contains(key);
}

std::string TomlTable::location(const std::string& key) const
{
  const toml::node* found = m_table->get(key);
  // A key set on the command line (--set) is named by its assignment, not by the file.
  if (found && found->source().path && *found->source().path != m_file)
    return *found->source().path;
  const auto line = found ? found->source().begin.line : 0;
  return line > 0 ? fmt::format("{}:{}", m_file, line) : m_file;
}

std::string TomlTable::child_label(const std::string& key, std::optional<std::size_t> index) const
{
  const bool plain_table = m_label.size() > 2 && m_label[0] == '[' && m_label[1] != '[';
  const std::string path = plain_table ? m_label.substr(1, m_label.size() - 2) + "." + key : key;
  const std::string own = index ? fmt::format("[[{}]] #{}", path, *index + 1) : "[" + path + "]";
  return m_label.empty() || plain_table ? own : m_label + " " + own;
}

void TomlTable::fail_at(const std::string& key, const std::string& problem) const
{
  fail("{}: {}{}: {}", location(key), m_label.empty() ? "" : m_label + " ", key, problem);
}

const toml::node& TomlTable::node(const std::string& key)
{
  m_read.insert(key);
  const toml::node* found = m_table->get(key);
  if (!found)
    fail_at(key, "missing");
  return *found;
}

double TomlTable::required_number(const std::string& key)
{
  const std::optional<double> number = toml_number(node(key));
  if (!number)
    fail_at(key, "expected a number");
  if (!std::isfinite(*number))
    fail_at(key, "expected a finite number");
  return *number;
}

double TomlTable::number(const std::string& key, double fallback)
{
  return has(key) ? required_number(key) : fallback;
}

int TomlTable::integer(const std::string& key, int fallback)
{
  if (!has(key))
    return fallback;
  const std::optional<int> value = toml_int(node(key));
  if (!value)
    fail_at(key, "expected an integer (at most 2147483647 in size)");
  return *value;
}

bool TomlTable::boolean(const std::string& key, bool fallback)
{
  if (!has(key))
    return fallback;
  const toml::node& value = node(key);
  if (!value.is_boolean())
    fail_at(key, "expected true or false");
  return value.value<bool>().value();
}

std::string TomlTable::required_text(const std::string& key)
{
  const toml::node& value = node(key);
  if (!value.is_string())
    fail_at(key, "expected a string");
  return value.value<std::string>().value();
}

std::string TomlTable::label(const std::string& key, const std::string& fallback)
{
  if (!has(key))
    return fallback;
  const toml::node& value = node(key);
  if (const std::optional<int64_t> number = value.value_exact<int64_t>())
    return std::to_string(*number);
  if (value.is_string())
    return value.value<std::string>().value();
  fail_at(key, "expected a label number or name");
}

std::string TomlTable::text(const std::string& key, const std::string& fallback)
{
  return has(key) ? required_text(key) : fallback;
}

Eigen::Vector3d TomlTable::required_vector3(const std::string& key)
{
  const toml::node& value = node(key);
  const toml::array* array = value.as_array();
  if (!array || array->size() != 3)
    fail_at(key, "expected an array of 3 numbers");
  Eigen::Vector3d result;
  for (std::size_t i = 0; i < 3; ++i) {
    const std::optional<double> item = toml_number(*array->get(i));
    if (!item || !std::isfinite(*item))
      fail_at(key, "expected an array of 3 finite numbers");
    result(static_cast<Eigen::Index>(i)) = *item;
  }
  return result;
}

Eigen::Vector3d TomlTable::vector3(const std::string& key, const Eigen::Vector3d& fallback)
{
  return has(key) ? required_vector3(key) : fallback;
}

Eigen::Vector3i TomlTable::integer_vector3(const std::string& key)
{
  const std::vector<int> values = integers(key);
  if (values.size() != 3)
    fail_at(key, "expected an array of 3 integers");
  return {values[0], values[1], values[2]};
}

std::vector<int> TomlTable::integers(const std::string& key)
{
  const toml::array* array = node(key).as_array();
  if (!array)
    fail_at(key, "expected an array of integers");
  std::vector<int> values;
  for (const toml::node& item : *array) {
    const std::optional<int> value = toml_int(item);
    if (!value)
      fail_at(key, "expected an array of integers (each at most 2147483647 in size)");
    values.push_back(*value);
  }
  return values;
}

std::vector<std::string> TomlTable::texts(const std::string& key)
{
  const toml::array* array = node(key).as_array();
  if (!array)
    fail_at(key, "expected an array of strings");
  std::vector<std::string> values;
  for (const toml::node& item : *array) {
    if (!item.is_string())
      fail_at(key, "expected an array of strings");
    values.push_back(item.value<std::string>().value());
  }
  return values;
}

std::vector<double> TomlTable::numbers(const std::string& key)
{
  const toml::array* array = node(key).as_array();
  if (!array)
    fail_at(key, "expected an array of numbers");
  std::vector<double> values;
  for (const toml::node& item : *array) {
    const std::optional<double> value = toml_number(item);
    if (!value || !std::isfinite(*value))
      fail_at(key, "expected an array of finite numbers");
    values.push_back(*value);
  }
  return values;
}

std::vector<std::vector<double>> TomlTable::number_lists(const std::string& key)
{
  const toml::array* array = node(key).as_array();
  if (!array)
    fail_at(key, "expected an array of arrays of numbers");
  std::vector<std::vector<double>> lists;
  for (const toml::node& item : *array) {
    const toml::array* list = item.as_array();
    if (!list)
      fail_at(key, "expected an array of arrays of numbers");
    std::vector<double>& values = lists.emplace_back();
    for (const toml::node& entry : *list) {
      const std::optional<double> value = toml_number(entry);
      if (!value || !std::isfinite(*value))
        fail_at(key, "expected arrays of finite numbers");
      values.push_back(*value);
    }
  }
  return lists;
}

std::optional<TomlTable> TomlTable::table(const std::string& key)
{
  if (!has(key))
    return std::nullopt;
  const toml::table* sub = node(key).as_table();
  if (!sub)
    fail_at(key, "expected a table");
  return TomlTable(*sub, m_file, child_label(key));
}

TomlTable TomlTable::required_table(const std::string& key)
{
  std::optional<TomlTable> sub = table(key);
  if (!sub)
    fail_at(key, "missing (a table)");
  return std::move(*sub);
}

std::vector<TomlTable> TomlTable::tables(const std::string& key)
{
  std::vector<TomlTable> result;
  if (!has(key))
    return result;
  const toml::array* array = node(key).as_array();
  if (!array)
    fail_at(key, "expected an array of tables ([[" + key + "]])");
  for (std::size_t i = 0; i < array->size(); ++i) {
    const toml::table* sub = array->get(i)->as_table();
    if (!sub)
      fail_at(key, "expected an array of tables ([[" + key + "]])");
    result.emplace_back(*sub, m_file, child_label(key, i));
  }
  return result;
}

std::vector<std::string> TomlTable::keys() const
{
  std::vector<std::string> names;
  for (const auto& [key, value] : *m_table)
    names.emplace_back(key.str());
  return names;
}

void TomlTable::only(const std::vector<std::string_view>& allowed) const
{
  for (const auto& [key, value] : *m_table)
    if (std::find(allowed.begin(), allowed.end(), key.str()) == allowed.end())
      fail("{}: unknown key '{}' in {}", location(std::string(key.str())), key.str(),
           m_label.empty() ? "the top level" : m_label);
}

void TomlTable::reject_unknown_keys() const
{
  for (const auto& [key, value] : *m_table)
    if (m_read.count(std::string(key.str())) == 0)
      fail("{}: unknown key '{}' in {}", location(std::string(key.str())), key.str(),
           m_label.empty() ? "the top level" : m_label);
}

} // namespace ligsim
