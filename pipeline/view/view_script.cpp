#include "pipeline/view/view_script.hpp"

#include "common/error.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

namespace ligsim::cli {

namespace {

std::vector<std::string> split(const std::string& line)
{
  std::vector<std::string> cells;
  std::stringstream stream(line);
  for (std::string cell; std::getline(stream, cell, ',');) {
    cell.erase(0, cell.find_first_not_of(" \t\r"));
    cell.erase(cell.find_last_not_of(" \t\r") + 1);
    cells.push_back(cell);
  }
  return cells;
}

} // namespace

ViewScript ViewScript::read(const std::filesystem::path& csv,
                            const std::vector<std::string>& columns)
{
  std::ifstream in(csv);
  if (!in)
    fail("view script '{}' cannot be read", csv.string());
  std::string line;
  if (!std::getline(in, line))
    fail("view script '{}' is empty", csv.string());
  const std::vector<std::string> header = split(line);
  const std::string needed = fmt::format("time_s, {}", fmt::join(columns, ", "));
  const auto column = [&](const std::string& name) {
    const auto found = std::find(header.begin(), header.end(), name);
    if (found == header.end())
      fail("view script '{}': the header has no column {} (it needs {})", csv.string(), name,
           needed);
    return static_cast<std::size_t>(found - header.begin());
  };
  const std::size_t time_column = column("time_s");
  std::vector<std::size_t> value_columns;
  for (const std::string& name : columns)
    value_columns.push_back(column(name));
  ViewScript script;
  script.m_values.resize(columns.size());
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.find_first_not_of(" \t\r") == std::string::npos)
      continue;
    const std::vector<std::string> cells = split(line);
    double time = NAN;
    std::vector<double> values(columns.size(), NAN);
    try {
      time = std::stod(cells.at(time_column));
      for (std::size_t c = 0; c < columns.size(); ++c)
        values[c] = std::stod(cells.at(value_columns[c]));
    } catch (const std::exception&) {
      fail("view script '{}' line {}: '{}' does not give {}", csv.string(), number, line, needed);
    }
    const bool finite =
        std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
    if (!std::isfinite(time) || !finite || time < 0.0 ||
        (!script.m_times.empty() && time <= script.m_times.back()))
      fail("view script '{}' line {}: times must be finite, from 0, strictly increasing, and "
           "every value finite (got '{}')",
           csv.string(), number, line);
    script.m_times.push_back(time);
    for (std::size_t c = 0; c < columns.size(); ++c)
      script.m_values[c].push_back(values[c]);
  }
  if (script.m_times.empty())
    fail("view script '{}' has no rows", csv.string());
  return script;
}

double ViewScript::at(double time_s, std::size_t column) const
{
  const std::vector<double>& values = m_values.at(column);
  if (time_s <= m_times.front())
    return values.front();
  if (time_s >= m_times.back())
    return values.back();
  const auto next = std::upper_bound(m_times.begin(), m_times.end(), time_s);
  const auto k = static_cast<std::size_t>(next - m_times.begin());
  const double w = (time_s - m_times[k - 1]) / (m_times[k] - m_times[k - 1]);
  return (1.0 - w) * values[k - 1] + w * values[k];
}

} // namespace ligsim::cli
