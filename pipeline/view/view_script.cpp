#include "pipeline/view/view_script.hpp"

#include "common/error.hpp"

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

ViewScript ViewScript::read(const std::filesystem::path& csv)
{
  std::ifstream in(csv);
  if (!in)
    fail("view script '{}' cannot be read", csv.string());
  std::string line;
  if (!std::getline(in, line))
    fail("view script '{}' is empty", csv.string());
  const std::vector<std::string> header = split(line);
  const auto column = [&](const char* name) {
    const auto found = std::find(header.begin(), header.end(), name);
    if (found == header.end())
      fail("view script '{}': the header has no column {} (it needs time_s and angle_deg)",
           csv.string(), name);
    return static_cast<std::size_t>(found - header.begin());
  };
  const std::size_t time_column = column("time_s"), angle_column = column("angle_deg");
  ViewScript script;
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.find_first_not_of(" \t\r") == std::string::npos)
      continue;
    const std::vector<std::string> cells = split(line);
    double time = NAN, angle = NAN;
    try {
      time = std::stod(cells.at(time_column));
      angle = std::stod(cells.at(angle_column));
    } catch (const std::exception&) {
      fail("view script '{}' line {}: '{}' is not a time and an angle", csv.string(), number, line);
    }
    if (!std::isfinite(time) || !std::isfinite(angle) || time < 0.0 ||
        (!script.m_times.empty() && time <= script.m_times.back()))
      fail("view script '{}' line {}: times must be finite, from 0, strictly increasing (got "
           "{} s, {} deg)",
           csv.string(), number, time, angle);
    script.m_times.push_back(time);
    script.m_angles.push_back(angle);
  }
  if (script.m_times.empty())
    fail("view script '{}' has no rows", csv.string());
  return script;
}

double ViewScript::angle_at(double time_s) const
{
  if (time_s <= m_times.front())
    return m_angles.front();
  if (time_s >= m_times.back())
    return m_angles.back();
  const auto next = std::upper_bound(m_times.begin(), m_times.end(), time_s);
  const auto k = static_cast<std::size_t>(next - m_times.begin());
  const double w = (time_s - m_times[k - 1]) / (m_times[k] - m_times[k - 1]);
  return (1.0 - w) * m_angles[k - 1] + w * m_angles[k];
}

} // namespace ligsim::cli
