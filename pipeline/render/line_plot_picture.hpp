#pragma once
/// @brief A PNG line plot with markers (VTK charts, rendered off-screen): strain energy against
/// flexion angle. Needs an X display, as every VTK picture here (OffscreenDisplay).

#include <filesystem>
#include <string>
#include <vector>

namespace ligsim::render {

struct LinePlot {
  std::string title, x_label, y_label;
  std::vector<double> x, y; ///< the same length, at least one point, finite
  int width = 900, height = 600;
};

/// Draws `plot` (white background, dark blue line with circles) and writes `png` atomically.
/// Throws InputError on mismatched, empty or non-finite data, a bad size or a failed write.
void render_line_plot_png(const LinePlot& plot, const std::filesystem::path& png);

} // namespace ligsim::render
