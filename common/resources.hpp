#pragma once
/// @brief Wall time and peak memory of a piece of work, for summary.json and benchmarks.

#include <chrono>

namespace ligsim {

/// Wall seconds since `start` (steady clock).
double seconds_since(std::chrono::steady_clock::time_point start);

/// Peak resident set size of this process since start or since the last reset, MiB.
double peak_rss_mib();

/// Resets the kernel's peak-RSS mark (Linux /proc/self/clear_refs), so the next
/// peak_rss_mib() covers only what follows. Harmless where unsupported.
void reset_peak_rss();

/// Measures one stage: wall seconds and the peak memory reached while it ran.
class StageMeter {
public:
  StageMeter();
  double wall_s() const;
  double peak_rss_mib() const;

private:
  std::chrono::steady_clock::time_point m_start;
};

} // namespace ligsim
