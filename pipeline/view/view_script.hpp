#pragma once
/// @brief A played interaction for `ligsim view --script`: values over simulated time, read from
/// a CSV with the column time_s and the values' columns (a knee's slider: angle_deg; a hand
/// pulling a membrane: x_mm and y_mm).

#include <filesystem>
#include <string>
#include <vector>

namespace ligsim::cli {

class ViewScript {
public:
  /// Reads `csv` (a header naming time_s and `columns`, then rows, times strictly increasing
  /// from 0 or later). Throws InputError naming the file and line of what is wrong.
  static ViewScript read(const std::filesystem::path& csv,
                         const std::vector<std::string>& columns = {"angle_deg"});

  /// Value `column` (in the order read() was given them) at `time_s`: linear between rows, held
  /// before the first and after the last.
  double at(double time_s, std::size_t column = 0) const;
  double start_s() const { return m_times.front(); }
  double end_s() const { return m_times.back(); }

private:
  std::vector<double> m_times;
  std::vector<std::vector<double>> m_values; ///< per column, per row
};

} // namespace ligsim::cli
