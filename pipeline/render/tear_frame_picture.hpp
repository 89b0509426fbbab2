#pragma once
/// @brief A picture of a tearing frame: the deformed membrane shaded by the criterion (pale
/// below 1/2, orange, red at 1 and above), thin element edges, the fibers as short strokes,
/// and the crack faces in black.

#include "pipeline/render/raster_image.hpp"
#include "sim/membrane/scene/tear_simulation.hpp"

#include <vector>

namespace ligsim::render {

/// The view: the rest configuration's bounding box with a margin of `margin` x its size, so
/// every frame of a run shares it. `size_px` is the larger side of the image.
struct FrameView {
  Eigen::Vector2d low_mm = Eigen::Vector2d::Zero();
  Eigen::Vector2d high_mm = Eigen::Vector2d::Ones();
  int size_px = 800;
};

FrameView frame_view(const membrane::MembraneMesh& mesh, int size_px, double margin = 0.15);

/// `criterion`: one value per triangle (Tearing::element_criterion).
RasterImage render_frame(const membrane::TearSimulation& simulation,
                         const std::vector<double>& criterion, const FrameView& view);

/// The colour of a criterion value.
Rgb criterion_colour(double criterion);

} // namespace ligsim::render
