#include "sim/febio/febio_log.hpp"

#include "common/error.hpp"

#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>

namespace ligsim::sim {

namespace {

bool starts_with(const std::string& text, const std::string& prefix)
{
  return text.compare(0, prefix.size(), prefix) == 0;
}

/// The value after "Key = " on `line`, or nothing when the line is not that key.
bool key_value(const std::string& line, const std::string& key, std::string& value)
{
  const std::string prefix = key + " = ";
  if (!starts_with(line, prefix))
    return false;
  value = line.substr(prefix.size());
  return true;
}

/// FEBio's boxed messages: " * text *" lines; the text without the frame.
std::string box_text(const std::string& line)
{
  std::string text = line;
  const std::size_t first = text.find('*');
  const std::size_t last = text.rfind('*');
  if (first == std::string::npos || last <= first)
    return {};
  text = text.substr(first + 1, last - first - 1);
  const std::size_t begin = text.find_first_not_of(' ');
  const std::size_t end = text.find_last_not_of(' ');
  return begin == std::string::npos ? std::string() : text.substr(begin, end - begin + 1);
}

} // namespace

const FebioRecord* FebioLog::find(int record, double time) const
{
  for (const FebioRecord& r : records)
    if (r.record == record && std::abs(r.time - time) < 1e-9)
      return &r;
  return nullptr;
}

FebioLog parse_febio_log(const std::string& text, const std::string& name)
{
  FebioLog log;
  std::istringstream in(text);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r')
      line.pop_back();
    lines.push_back(line);
  }
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string& line = lines[i];
    if (line.find("N O R M A L   T E R M I N A T I O N") != std::string::npos)
      log.normal_termination = true;
    if (line.find("E R R O R   T E R M I N A T I O N") != std::string::npos)
      log.error_termination = true;
    if (box_text(line) == "ERROR") {
      // The message follows in the box until its closing line of stars. FEBio recovers from
      // some (a time step cut back): the last one is what ended a failed run.
      log.error.clear();
      for (std::size_t j = i + 1; j < lines.size() && lines[j].find("****") == std::string::npos;
           ++j) {
        const std::string part = box_text(lines[j]);
        if (!part.empty())
          log.error += (log.error.empty() ? "" : " ") + part;
      }
      if (log.error.empty())
        log.error = "FEBio reported an error";
    }
    if (!starts_with(line, "Data Record #"))
      continue;
    FebioRecord record;
    record.record = std::atoi(line.c_str() + 13);
    std::size_t j = i + 1;
    std::string value;
    bool has_data = false;
    for (; j < lines.size() && !has_data; ++j) {
      if (key_value(lines[j], "Step", value))
        record.step = std::atoi(value.c_str());
      else if (key_value(lines[j], "Time", value))
        record.time = std::strtod(value.c_str(), nullptr);
      else if (key_value(lines[j], "Data", value)) {
        std::istringstream names(value);
        for (std::string variable; std::getline(names, variable, ';');)
          record.variables.push_back(variable);
        has_data = true;
      }
    }
    if (!has_data)
      fail("{}, line {}: data record without a 'Data = ' line", name, i + 1);
    for (; j < lines.size() && !lines[j].empty(); ++j) {
      std::istringstream row(lines[j]);
      int id = 0;
      if (!(row >> id))
        break;
      std::vector<double> values;
      for (double v; row >> v;)
        values.push_back(v);
      if (values.size() != record.variables.size())
        fail("{}, line {}: {} values for the {} variables '{}'", name, j + 1, values.size(),
             record.variables.size(), value);
      record.rows[id] = values;
    }
    log.records.push_back(std::move(record));
    i = j - 1;
  }
  return log;
}

FebioLog read_febio_log(const std::filesystem::path& file)
{
  std::ifstream in(file);
  if (!in)
    fail("cannot read FEBio's log {}", file.string());
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  return parse_febio_log(text, file.string());
}

} // namespace ligsim::sim
