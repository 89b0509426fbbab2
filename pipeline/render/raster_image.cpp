#include "pipeline/render/raster_image.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>

#include <algorithm>
#include <cmath>

namespace ligsim::render {
namespace {

double edge_function(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p)
{
  return (b.x() - a.x()) * (p.y() - a.y()) - (b.y() - a.y()) * (p.x() - a.x());
}

/// Top-left rule: a pixel centre exactly on an edge belongs to the triangle only for a top or
/// left edge, so a pixel on an edge shared by two triangles is drawn once.
bool owns_edge(const Eigen::Vector2d& a, const Eigen::Vector2d& b)
{
  const Eigen::Vector2d d = b - a;
  return (d.y() == 0.0 && d.x() > 0.0) || d.y() < 0.0;
}

} // namespace

RasterImage::RasterImage(int width, int height, const Rgb& background)
    : m_width(width)
    , m_height(height)
    , m_pixels(static_cast<std::size_t>(std::max(0, width)) * std::max(0, height), background)
{
  if (width < 1 || height < 1 || width > 16384 || height > 16384)
    fail("image size {} x {} pixels is out of range (1 to 16384)", width, height);
}

void RasterImage::set(int x, int y, const Rgb& colour)
{
  if (x >= 0 && y >= 0 && x < m_width && y < m_height)
    m_pixels[static_cast<std::size_t>(y) * m_width + x] = colour;
}

void RasterImage::fill_triangle(const Eigen::Vector2d& a0, const Eigen::Vector2d& b0,
                                const Eigen::Vector2d& c, const Rgb& colour)
{
  // Make the corners counter-clockwise in the image's y-down frame (positive edge functions).
  Eigen::Vector2d a = a0, b = b0;
  double area = edge_function(a, b, c);
  if (area == 0.0 || !std::isfinite(area))
    return;
  if (area < 0.0) {
    std::swap(a, b);
    area = -area;
  }
  const int x_min = std::max(0, static_cast<int>(std::floor(std::min({a.x(), b.x(), c.x()}))));
  const int x_max =
      std::min(m_width - 1, static_cast<int>(std::ceil(std::max({a.x(), b.x(), c.x()}))));
  const int y_min = std::max(0, static_cast<int>(std::floor(std::min({a.y(), b.y(), c.y()}))));
  const int y_max =
      std::min(m_height - 1, static_cast<int>(std::ceil(std::max({a.y(), b.y(), c.y()}))));
  for (int y = y_min; y <= y_max; ++y)
    for (int x = x_min; x <= x_max; ++x) {
      const Eigen::Vector2d p(x + 0.5, y + 0.5);
      const double w0 = edge_function(b, c, p), w1 = edge_function(c, a, p),
                   w2 = edge_function(a, b, p);
      const bool inside = (w0 > 0.0 || (w0 == 0.0 && owns_edge(b, c))) &&
                          (w1 > 0.0 || (w1 == 0.0 && owns_edge(c, a))) &&
                          (w2 > 0.0 || (w2 == 0.0 && owns_edge(a, b)));
      if (inside)
        set(x, y, colour);
    }
}

void RasterImage::draw_line(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double thickness,
                            const Rgb& colour)
{
  const Eigen::Vector2d d = b - a;
  const double length = d.norm();
  const double radius = 0.5 * std::max(1.0, thickness);
  if (!std::isfinite(length))
    return;
  const int x_min = std::max(0, static_cast<int>(std::floor(std::min(a.x(), b.x()) - radius)));
  const int x_max =
      std::min(m_width - 1, static_cast<int>(std::ceil(std::max(a.x(), b.x()) + radius)));
  const int y_min = std::max(0, static_cast<int>(std::floor(std::min(a.y(), b.y()) - radius)));
  const int y_max =
      std::min(m_height - 1, static_cast<int>(std::ceil(std::max(a.y(), b.y()) + radius)));
  for (int y = y_min; y <= y_max; ++y)
    for (int x = x_min; x <= x_max; ++x) {
      const Eigen::Vector2d p(x + 0.5, y + 0.5);
      const double t =
          length > 0.0 ? std::clamp((p - a).dot(d) / (length * length), 0.0, 1.0) : 0.0;
      if ((a + t * d - p).norm() <= radius)
        set(x, y, colour);
    }
}

void RasterImage::write_png(const std::filesystem::path& file) const
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(m_width, m_height, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* data = static_cast<std::uint8_t*>(image->GetScalarPointer());
  // VTK images start at the bottom row.
  for (int y = 0; y < m_height; ++y)
    for (int x = 0; x < m_width; ++x) {
      const Rgb& colour = pixel(x, m_height - 1 - y);
      std::copy(colour.begin(), colour.end(),
                data + 3 * (static_cast<std::size_t>(y) * m_width + x));
    }
  AtomicFile out(file);
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(out.temp_path().string().c_str());
  writer->SetInputData(image);
  writer->Write();
  if (writer->GetErrorCode() != 0)
    fail("cannot write PNG {}", file.string());
  out.commit();
}

} // namespace ligsim::render
