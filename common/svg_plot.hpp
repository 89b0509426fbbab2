#pragma once
/// @brief A small SVG line plot (axes, optional log scales, labelled points, legend), enough
/// for the figures the verification jobs write next to their CSV files.

#include <string>
#include <vector>

namespace ligsim {

struct PlotSeries {
  std::string name;
  std::vector<double> x;
  std::vector<double> y;
  std::vector<std::string> point_labels; ///< optional, one per point
};

struct PlotSpec {
  std::string title;
  std::string x_label;
  std::string y_label;
  bool log_x = false;
  bool log_y = false;
  std::vector<PlotSeries> series;
};

/// The plot as a standalone SVG document. Points that cannot be drawn (non-finite, or not
/// positive on a log axis) are left out.
std::string svg_line_plot(const PlotSpec& spec);

} // namespace ligsim
