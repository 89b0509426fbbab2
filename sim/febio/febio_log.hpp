#pragma once
/// @brief FEBio's .log as ligsim reads it: whether the run ended normally, the first error it
/// reports, and the data records of the <logfile> section (one per entry and time step).

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace ligsim::sim {

/// One data record at one time: the values of each item (a node, element or rigid body id).
struct FebioRecord {
  int record = 0; ///< "Data Record #n": n is the entry's place in <logfile>, from 1
  int step = 0;
  double time = 0.0;
  std::vector<std::string> variables;      ///< "x", "y", ...
  std::map<int, std::vector<double>> rows; ///< item id (1-based) -> one value per variable
};

struct FebioLog {
  bool normal_termination = false;
  bool error_termination = false;
  std::string error; ///< the text of FEBio's last ERROR box, if any
  std::vector<FebioRecord> records;

  /// The record `record` at time `time` (within 1e-9), or nullptr.
  const FebioRecord* find(int record, double time) const;
};

/// Parses the text of a .log. Throws InputError naming `name` and the line of a malformed
/// record.
FebioLog parse_febio_log(const std::string& text, const std::string& name);

/// Reads and parses `file` (InputError when it cannot be read).
FebioLog read_febio_log(const std::filesystem::path& file);

} // namespace ligsim::sim
