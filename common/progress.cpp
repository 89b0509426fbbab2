#include "common/progress.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cstdio>

namespace ligsim {

namespace {
std::atomic<bool> g_quiet{false};
/// Work shorter than this reports only its closing line.
constexpr double kQuietSeconds = 1.0;
} // namespace

Progress::Progress(std::string label, std::size_t total)
    : m_label(std::move(label))
    , m_total(total)
    , m_start(std::chrono::steady_clock::now())
{
}

void Progress::advance(std::size_t count)
{
  m_done += count;
  if (m_total == 0 || g_quiet)
    return;
  const int tenth = static_cast<int>(10 * std::min(m_done, m_total) / m_total);
  if (tenth > m_reported_tenth && tenth < 10 && elapsed_s() >= kQuietSeconds) {
    m_reported_tenth = tenth;
    fmt::print(stderr, "  {}: {}%\n", m_label, 10 * tenth);
  }
}

void Progress::finish()
{
  if (m_finished)
    return;
  m_finished = true;
  if (g_quiet)
    return;
  fmt::print(stderr, "  {}: done in {:.2f} s\n", m_label, elapsed_s());
}

double Progress::elapsed_s() const
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
}

void Progress::set_quiet(bool quiet)
{
  g_quiet = quiet;
}

void log_info(const std::string& message)
{
  if (!g_quiet)
    fmt::print(stderr, "ligsim: {}\n", message);
}

} // namespace ligsim
