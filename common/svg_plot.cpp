#include "common/svg_plot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace ligsim {

namespace {

constexpr double width = 760;
constexpr double height = 480;
constexpr double left = 80;
constexpr double right = 220; // room for the legend
constexpr double top = 40;
constexpr double bottom = 60;
constexpr std::array<const char*, 8> colours = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e",
                                                "#9467bd", "#8c564b", "#e377c2", "#17becf"};

struct Axis {
  bool log = false;
  double low = 0.0;
  double high = 1.0;

  bool drawable(double v) const { return std::isfinite(v) && (!log || v > 0.0); }
  double map(double v) const { return log ? std::log10(v) : v; }
  /// Fraction of the axis length, 0 at `low`.
  double fraction(double v) const { return (map(v) - map(low)) / (map(high) - map(low)); }

  std::vector<double> ticks() const
  {
    std::vector<double> result;
    if (log) {
      for (double e = std::floor(std::log10(low)); e <= std::ceil(std::log10(high)); e += 1.0) {
        const double v = std::pow(10.0, e);
        if (v >= low * (1 - 1e-9) && v <= high * (1 + 1e-9))
          result.push_back(v);
      }
      return result;
    }
    const double span = high - low;
    const double step = std::pow(10.0, std::floor(std::log10(span / 4)));
    const double nice = span / step > 20 ? 5 * step : span / step > 8 ? 2 * step : step;
    for (double v = std::ceil(low / nice) * nice; v <= high + 1e-12 * span; v += nice)
      result.push_back(v);
    return result;
  }
};

Axis make_axis(bool log, const std::vector<double>& values)
{
  Axis axis;
  axis.log = log;
  double low = std::numeric_limits<double>::infinity();
  double high = -low;
  for (double v : values)
    if (axis.drawable(v)) {
      low = std::min(low, v);
      high = std::max(high, v);
    }
  if (!std::isfinite(low)) {
    low = log ? 1.0 : 0.0;
    high = log ? 10.0 : 1.0;
  }
  if (log) {
    axis.low = std::pow(10.0, std::floor(std::log10(low)));
    axis.high = std::pow(10.0, std::ceil(std::log10(high)));
    if (axis.high <= axis.low)
      axis.high = axis.low * 10.0;
  } else {
    const double pad = high > low ? 0.05 * (high - low) : 1.0;
    axis.low = low - pad;
    axis.high = high + pad;
  }
  return axis;
}

std::string escape(const std::string& text)
{
  std::string out;
  for (char c : text) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else
      out += c;
  }
  return out;
}

std::string tick_text(double v)
{
  return fmt::format("{:g}", v);
}

} // namespace

std::string svg_line_plot(const PlotSpec& spec)
{
  std::vector<double> xs;
  std::vector<double> ys;
  for (const PlotSeries& s : spec.series) {
    xs.insert(xs.end(), s.x.begin(), s.x.end());
    ys.insert(ys.end(), s.y.begin(), s.y.end());
  }
  const Axis x_axis = make_axis(spec.log_x, xs);
  const Axis y_axis = make_axis(spec.log_y, ys);
  const double plot_w = width - left - right;
  const double plot_h = height - top - bottom;
  auto px = [&](double v) { return left + x_axis.fraction(v) * plot_w; };
  auto py = [&](double v) { return top + (1.0 - y_axis.fraction(v)) * plot_h; };

  std::string svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\" "
      "font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" "
      "fill=\"white\"/>\n<text x=\"{}\" y=\"22\" font-size=\"15\" "
      "text-anchor=\"middle\">{}</text>\n",
      width, height, left + plot_w / 2, escape(spec.title));
  svg += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" "
                     "stroke=\"black\"/>\n",
                     left, top, plot_w, plot_h);
  for (double t : x_axis.ticks())
    svg += fmt::format("<line x1=\"{0}\" y1=\"{1}\" x2=\"{0}\" y2=\"{2}\" stroke=\"#ddd\"/>"
                       "<text x=\"{0}\" y=\"{3}\" text-anchor=\"middle\">{4}</text>\n",
                       px(t), top, top + plot_h, top + plot_h + 16, tick_text(t));
  for (double t : y_axis.ticks())
    svg += fmt::format("<line x1=\"{0}\" y1=\"{1}\" x2=\"{2}\" y2=\"{1}\" stroke=\"#ddd\"/>"
                       "<text x=\"{3}\" y=\"{4}\" text-anchor=\"end\">{5}</text>\n",
                       left, py(t), left + plot_w, left - 6, py(t) + 4, tick_text(t));
  svg += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n",
                     left + plot_w / 2, height - 18, escape(spec.x_label));
  svg += fmt::format("<text x=\"18\" y=\"{0}\" text-anchor=\"middle\" "
                     "transform=\"rotate(-90 18 {0})\">{1}</text>\n",
                     top + plot_h / 2, escape(spec.y_label));

  for (std::size_t s = 0; s < spec.series.size(); ++s) {
    const PlotSeries& series = spec.series[s];
    const char* colour = colours[s % colours.size()];
    std::string path;
    for (std::size_t i = 0; i < series.x.size() && i < series.y.size(); ++i) {
      if (!x_axis.drawable(series.x[i]) || !y_axis.drawable(series.y[i]))
        continue;
      const double x = px(series.x[i]);
      const double y = py(series.y[i]);
      path += fmt::format("{}{:.1f},{:.1f} ", path.empty() ? "M" : "L", x, y);
      svg += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"3.5\" fill=\"{}\"/>\n", x, y,
                         colour);
      if (i < series.point_labels.size())
        svg +=
            fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"10\" fill=\"{}\">{}</text>\n",
                        x + 5, y - 5, colour, escape(series.point_labels[i]));
    }
    if (!path.empty())
      svg += fmt::format("<path d=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"1.5\"/>\n",
                         path, colour);
    const double legend_y = top + 10 + 18 * static_cast<double>(s);
    svg += fmt::format("<line x1=\"{0}\" y1=\"{1}\" x2=\"{2}\" y2=\"{1}\" stroke=\"{3}\" "
                       "stroke-width=\"2\"/><text x=\"{4}\" y=\"{5}\">{6}</text>\n",
                       left + plot_w + 12, legend_y, left + plot_w + 32, colour, left + plot_w + 38,
                       legend_y + 4, escape(series.name));
  }
  svg += "</svg>\n";
  return svg;
}

} // namespace ligsim
