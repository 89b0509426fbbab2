#pragma once
/// @brief Progress of long work on stderr: one line per tenth once the work has run for a
/// second, so logs stay readable.

#include <chrono>
#include <cstddef>
#include <string>

namespace ligsim {

class Progress {
public:
  /// `label` names the work ("distance"), `total` counts its units.
  Progress(std::string label, std::size_t total);

  /// Marks `count` more units done; prints when a new tenth is reached.
  void advance(std::size_t count = 1);

  /// Prints the closing line with the elapsed time.
  void finish();

  /// Silences every Progress (tests, --quiet).
  static void set_quiet(bool quiet);

private:
  double elapsed_s() const;

  std::string m_label;
  std::size_t m_total;
  std::size_t m_done = 0;
  int m_reported_tenth = 0;
  bool m_finished = false;
  std::chrono::steady_clock::time_point m_start;
};

/// One line on stderr, unless quiet: "ligsim: <message>".
void log_info(const std::string& message);

} // namespace ligsim
