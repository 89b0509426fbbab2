#include "common/resources.hpp"

#include <fstream>
#include <sstream>
#include <string>

namespace ligsim {

double peak_rss_mib()
{
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) {
      std::istringstream fields(line.substr(6));
      double kib = 0.0;
      fields >> kib;
      return kib / 1024.0;
    }
  }
  return 0.0;
}

void reset_peak_rss()
{
  // Writing 5 resets VmHWM to the current RSS (Linux >= 4.0).
  std::ofstream clear("/proc/self/clear_refs");
  if (clear)
    clear << "5";
}

double seconds_since(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

StageMeter::StageMeter()
    : m_start(std::chrono::steady_clock::now())
{
  reset_peak_rss();
}

double StageMeter::wall_s() const
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
}

double StageMeter::peak_rss_mib() const
{
  return ligsim::peak_rss_mib();
}

} // namespace ligsim
