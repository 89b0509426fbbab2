#pragma once
/// @brief A small software rasterizer: filled triangles and thick lines into an RGB image,
/// so frames render without OpenGL or an X server.

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

namespace ligsim::render {

using Rgb = std::array<std::uint8_t, 3>;

class RasterImage {
public:
  /// A `width` x `height` image filled with `background`. Pixel (0, 0) is the top left.
  RasterImage(int width, int height, const Rgb& background);

  int width() const { return m_width; }
  int height() const { return m_height; }
  const Rgb& pixel(int x, int y) const
  {
    return m_pixels[static_cast<std::size_t>(y) * m_width + x];
  }

  /// Fills the triangle with corners in pixel coordinates (x right, y down); a pixel is inside
  /// when its centre is (top-left rule on shared edges, so neighbours do not overlap).
  void fill_triangle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                     const Rgb& colour);

  /// Draws a segment `thickness` pixels wide.
  void draw_line(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double thickness,
                 const Rgb& colour);

  /// Writes a PNG (through VTK's PNG writer), atomically. Throws InputError on failure.
  void write_png(const std::filesystem::path& file) const;

private:
  void set(int x, int y, const Rgb& colour);

  int m_width;
  int m_height;
  std::vector<Rgb> m_pixels;
};

} // namespace ligsim::render
