#pragma once
/// @brief ParaView collection files (.pvd): a series of VTK files by time, written atomically.

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace ligsim {

/// A ParaView collection file: (time, file relative to the .pvd) pairs.
void write_pvd(const std::filesystem::path& file,
               const std::vector<std::pair<double, std::string>>& steps);

/// One file of a collection; files of the same time with different parts are shown together
/// (a ligament and its bones).
struct PvdDataSet {
  double time = 0.0;
  int part = 0;
  std::string file; ///< relative to the .pvd
};
void write_pvd(const std::filesystem::path& file, const std::vector<PvdDataSet>& data_sets);

} // namespace ligsim
