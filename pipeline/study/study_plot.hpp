#pragma once
/// @brief The studies' plots: several curves on one chart (log or linear axes, a legend), written
/// both as SVG (common/svg_plot) and as PNG (VTK charts rendered off-screen; needs an X display,
/// so create a render::OffscreenDisplay first).

#include "common/svg_plot.hpp"

#include <filesystem>

namespace ligsim::study {

/// Writes `<stem>.svg` and, if `png`, `<stem>.png`. Points that cannot be drawn (non-finite, or not
/// positive on a log axis) are left out of both; a series left with no point is left out.
/// Throws InputError if nothing at all can be drawn or a file cannot be written.
void write_plot(const PlotSpec& spec, const std::filesystem::path& stem, bool png);

} // namespace ligsim::study
