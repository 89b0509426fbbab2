#include "pipeline/render/tear_frame_picture.hpp"

#include "sim/membrane/mesh/membrane_mesh.hpp"

#include <algorithm>
#include <cmath>

namespace ligsim::render {

using membrane::MembraneMesh;
using membrane::TearSimulation;
using membrane::Triangle;
using membrane::Vec2;

namespace {

Rgb mix(const Rgb& a, const Rgb& b, double t)
{
  Rgb out;
  for (int i = 0; i < 3; ++i)
    out[i] = static_cast<std::uint8_t>(std::lround((1.0 - t) * a[i] + t * b[i]));
  return out;
}

} // namespace

Rgb criterion_colour(double criterion)
{
  const Rgb low{226, 231, 240}, middle{244, 190, 110}, high{196, 40, 28};
  const double c = std::isfinite(criterion) ? std::clamp(criterion, 0.0, 1.0) : 0.0;
  return c < 0.5 ? mix(low, middle, 2.0 * c) : mix(middle, high, 2.0 * c - 1.0);
}

FrameView frame_view(const MembraneMesh& mesh, int size_px, double margin)
{
  FrameView view;
  view.size_px = size_px;
  if (mesh.node_count() == 0)
    return view;
  Eigen::Vector2d low = mesh.rest[0], high = mesh.rest[0];
  for (const Vec2& p : mesh.rest) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  const Eigen::Vector2d pad = margin * (high - low).cwiseMax(1e-9);
  view.low_mm = low - pad;
  view.high_mm = high + pad;
  return view;
}

RasterImage render_frame(const TearSimulation& simulation, const std::vector<double>& criterion,
                         const FrameView& view)
{
  const MembraneMesh& mesh = simulation.mesh();
  const Eigen::Vector2d extent = view.high_mm - view.low_mm;
  const double scale = view.size_px / extent.maxCoeff(); // pixels per mm
  const int width = std::max(1, static_cast<int>(std::lround(extent.x() * scale)));
  const int height = std::max(1, static_cast<int>(std::lround(extent.y() * scale)));
  RasterImage image(width, height, Rgb{255, 255, 255});
  const auto pixel = [&](const Vec2& p) {
    return Eigen::Vector2d((p.x() - view.low_mm.x()) * scale, (view.high_mm.y() - p.y()) * scale);
  };

  for (int tri = 0; tri < mesh.triangle_count(); ++tri) {
    const Triangle& t = mesh.triangles[tri];
    image.fill_triangle(pixel(mesh.position[t[0]]), pixel(mesh.position[t[1]]),
                        pixel(mesh.position[t[2]]), criterion_colour(criterion[tri]));
  }
  const Rgb edge{170, 176, 190}, fiber{70, 80, 120}, crack{0, 0, 0};
  for (const Triangle& t : mesh.triangles)
    for (int k = 0; k < 3; ++k)
      image.draw_line(pixel(mesh.position[t[k]]), pixel(mesh.position[t[(k + 1) % 3]]), 1.0, edge);
  for (int tri = 0; tri < mesh.triangle_count(); ++tri) {
    const Triangle& t = mesh.triangles[tri];
    const Vec2 centre = (mesh.position[t[0]] + mesh.position[t[1]] + mesh.position[t[2]]) / 3.0;
    const double size = std::sqrt(2.0 * std::abs(rest_area(mesh, tri)));
    const Vec2 rotation = simulation.elements().rotation(tri);
    const double angle = mesh.fiber_angle_rad[tri] + std::atan2(rotation.y(), rotation.x());
    const Vec2 half = 0.3 * size * Vec2(std::cos(angle), std::sin(angle));
    image.draw_line(pixel(centre - half), pixel(centre + half), 1.0, fiber);
  }
  const double crack_width = std::max(2.0, view.size_px / 300.0);
  for (const auto& e : crack_edges(mesh))
    image.draw_line(pixel(mesh.position[e[0]]), pixel(mesh.position[e[1]]), crack_width, crack);
  return image;
}

} // namespace ligsim::render
