#include "sim/kinematics/kinematics_csv.hpp"

#include "common/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

namespace ligsim::sim {

namespace {

const std::array<const char*, 7> column_names = {
    "time_s",     "flexion_deg", "varus_deg",  "internal_rotation_deg",
    "lateral_mm", "anterior_mm", "proximal_mm"};

std::string trimmed(const std::string& text)
{
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos)
    return "";
  return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

std::vector<std::string> fields_of(const std::string& line)
{
  std::vector<std::string> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(trimmed(line.substr(start, comma - start)));
    if (comma == std::string::npos)
      return fields;
    start = comma + 1;
  }
}

double number_of(const std::string& field, const std::filesystem::path& file, int line,
                 const std::string& column)
{
  errno = 0;
  char* end = nullptr;
  const double value = std::strtod(field.c_str(), &end);
  if (field.empty() || end != field.c_str() + field.size() || errno == ERANGE ||
      !std::isfinite(value))
    fail("{}:{}: column {}: '{}' is not a finite number", file.string(), line, column, field);
  return value;
}

/// What a free run writes besides the coordinates (sim/flexion/free_flexion.hpp).
const std::array<const char*, 10> free_run_columns = {"medial_contact_force_n",
                                                      "lateral_contact_force_n",
                                                      "medial_contact_anterior_mm",
                                                      "medial_contact_medial_mm",
                                                      "lateral_contact_anterior_mm",
                                                      "lateral_contact_medial_mm",
                                                      "residual_force_n",
                                                      "residual_moment_nmm",
                                                      "converged",
                                                      "iterations"};

} // namespace

KneePath read_kinematics_csv(const std::filesystem::path& file)
{
  std::ifstream in(file);
  if (!in)
    fail("kinematics file {} cannot be opened", file.string());
  std::vector<int> column_of_field; // index into column_names per field, -1: skipped
  int medial_column = -1;           // the field that gives medial_mm (= -lateral_mm)
  std::vector<double> knots;
  std::vector<JointPose> poses;
  bool by_time = false;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const std::string text = trimmed(line);
    if (text.empty() || text.front() == '#')
      continue;
    const std::vector<std::string> fields = fields_of(text);
    if (column_of_field.empty()) {
      for (const std::string& name : fields) {
        // A free run's kinematics.csv reads as a table too: its angle and its medial shift name
        // the same coordinates, and its contact and residual columns are skipped.
        const std::string known = name == "angle_deg"   ? "flexion_deg"
                                  : name == "medial_mm" ? "lateral_mm"
                                                        : name;
        if (name == "medial_mm")
          medial_column = static_cast<int>(column_of_field.size());
        const auto found = std::find(column_names.begin(), column_names.end(), known);
        if (found == column_names.end() &&
            std::find(free_run_columns.begin(), free_run_columns.end(), name) !=
                free_run_columns.end()) {
          column_of_field.push_back(-1);
          continue;
        }
        if (found == column_names.end())
          fail("{}:{}: unknown column '{}' (the columns are {})", file.string(), number, name,
               fmt::join(column_names, ", "));
        const int column = static_cast<int>(found - column_names.begin());
        if (std::find(column_of_field.begin(), column_of_field.end(), column) !=
            column_of_field.end())
          fail("{}:{}: column '{}' is named twice", file.string(), number, name);
        column_of_field.push_back(column);
      }
      if (std::find(column_of_field.begin(), column_of_field.end(), 1) == column_of_field.end())
        fail("{}:{}: the header has no flexion_deg column", file.string(), number);
      by_time =
          std::find(column_of_field.begin(), column_of_field.end(), 0) != column_of_field.end();
      continue;
    }
    if (fields.size() != column_of_field.size())
      fail("{}:{}: {} fields where the header names {} columns", file.string(), number,
           fields.size(), column_of_field.size());
    std::array<double, 7> row = {};
    for (std::size_t f = 0; f < fields.size(); ++f) {
      if (column_of_field[f] < 0)
        continue;
      const auto column = static_cast<std::size_t>(column_of_field[f]);
      row[column] = number_of(fields[f], file, number, column_names[column]);
      if (static_cast<int>(f) == medial_column)
        row[column] = -row[column];
    }
    knots.push_back(by_time ? row[0] : row[1]);
    poses.push_back({row[1], row[2], row[3], row[4], row[5], row[6]});
  }
  if (column_of_field.empty() || poses.empty())
    fail("kinematics file {} has no {}", file.string(),
         column_of_field.empty() ? "header line" : "rows");
  return KneePath::table(by_time ? KneePath::Parameter::time_s : KneePath::Parameter::flexion_deg,
                         std::move(knots), std::move(poses), file.string());
}

} // namespace ligsim::sim
