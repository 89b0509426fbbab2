#include "common/pvd_file.hpp"

#include "common/atomic_file.hpp"

#include <sstream>

namespace ligsim {

namespace fs = std::filesystem;

void write_pvd(const fs::path& file, const std::vector<std::pair<double, std::string>>& steps)
{
  std::vector<PvdDataSet> data_sets;
  for (const auto& [time, name] : steps)
    data_sets.push_back({time, 0, name});
  write_pvd(file, data_sets);
}

void write_pvd(const fs::path& file, const std::vector<PvdDataSet>& data_sets)
{
  std::ostringstream out;
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
  for (const PvdDataSet& data : data_sets)
    out << "    <DataSet timestep=\"" << data.time << "\" part=\"" << data.part << "\" file=\""
        << data.file << "\"/>\n";
  out << "  </Collection>\n</VTKFile>\n";
  write_text_atomically(file, out.str());
}

} // namespace ligsim
