#pragma once
/// @brief A played interaction for `ligsim view --script`: the slider's angle over simulated
/// time, read from a CSV with the columns time_s and angle_deg.

#include <filesystem>
#include <vector>

namespace ligsim::cli {

class ViewScript {
public:
  /// Reads `csv` (a header naming time_s and angle_deg, then rows, times strictly increasing
  /// from 0 or later). Throws InputError naming the file and line of what is wrong.
  static ViewScript read(const std::filesystem::path& csv);

  /// The slider's angle at `time_s`: linear between rows, held before the first and after the last.
  double angle_at(double time_s) const;
  double end_s() const { return m_times.back(); }

private:
  std::vector<double> m_times;
  std::vector<double> m_angles;
};

} // namespace ligsim::cli
