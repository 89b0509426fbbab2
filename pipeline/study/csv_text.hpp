#pragma once
/// @brief Text fields of the studies' CSV files, quoted (RFC 4180), so that a family called
/// "quasi-static, mesh" or an error message stays one field.

#include <string>

namespace ligsim::study {

inline std::string csv_quoted(const std::string& text)
{
  std::string quoted = "\"";
  for (char c : text)
    quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

} // namespace ligsim::study
