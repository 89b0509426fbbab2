#include "sim/membrane/mesh/generate.hpp"

#include "common/error.hpp"
#include "sim/membrane/mesh/delaunay.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace ligsim::membrane {
namespace {

void check_size(double length_mm, double element_size_mm, const char* what)
{
  if (!(element_size_mm > 0.0) || !(length_mm > 0.0) || !std::isfinite(length_mm))
    fail("mesh: {} {} mm and element size {} mm must be positive", what, length_mm,
         element_size_mm);
  if (length_mm / element_size_mm > 2000.0)
    fail("mesh: {} {} mm over element size {} mm gives too many elements", what, length_mm,
         element_size_mm);
  if (length_mm / element_size_mm < 2.0)
    fail("mesh: element size {} mm is too large for a {} of {} mm", element_size_mm, what,
         length_mm);
}

MembraneMesh mesh_from(const std::vector<Vec2>& nodes, const std::vector<Triangle>& triangles)
{
  MembraneMesh mesh;
  for (const Vec2& p : nodes)
    mesh.add_node(p);
  for (const Triangle& t : triangles)
    mesh.add_triangle(t, 0.0, {false, false, false}, {0, 0, 0});
  return mesh;
}

} // namespace

MembraneMesh rectangle_mesh(double width_mm, double height_mm, double element_size_mm,
                            double jitter, std::uint64_t seed)
{
  check_size(width_mm, element_size_mm, "width");
  check_size(height_mm, element_size_mm, "height");
  const int columns = std::max(2, static_cast<int>(std::lround(width_mm / element_size_mm)));
  const int rows = std::max(
      2, static_cast<int>(std::lround(height_mm / (element_size_mm * std::sqrt(3.0) / 2.0))));
  const double dx = width_mm / columns, dy = height_mm / rows;
  const double x0 = -0.5 * width_mm, y0 = -0.5 * height_mm;

  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> shake(-jitter * element_size_mm, jitter * element_size_mm);
  std::vector<Vec2> nodes;
  std::vector<std::vector<int>> row_nodes(rows + 1);
  for (int j = 0; j <= rows; ++j) {
    std::vector<double> xs;
    if (j % 2 == 0) {
      for (int i = 0; i <= columns; ++i)
        xs.push_back(x0 + i * dx);
    } else { // offset row, closed by nodes on the left and right sides
      xs.push_back(x0);
      for (int i = 0; i < columns; ++i)
        xs.push_back(x0 + (i + 0.5) * dx);
      xs.push_back(x0 + width_mm);
    }
    for (std::size_t i = 0; i < xs.size(); ++i) {
      Vec2 p(xs[i], y0 + j * dy);
      // Nodes on the boundary, and the half-spaced ones next to it, stay on the lattice.
      const double from_side = std::min(xs[i] - x0, x0 + width_mm - xs[i]);
      const bool near_boundary = j == 0 || j == rows || from_side < 0.75 * dx;
      if (!near_boundary)
        p += Vec2(shake(random), shake(random));
      row_nodes[j].push_back(static_cast<int>(nodes.size()));
      nodes.push_back(p);
    }
  }
  // Zip each pair of rows: advance along the row whose next node comes first in x.
  std::vector<Triangle> triangles;
  for (int j = 0; j < rows; ++j) {
    const auto& low = row_nodes[j];
    const auto& high = row_nodes[j + 1];
    std::size_t i = 0, k = 0;
    while (i + 1 < low.size() || k + 1 < high.size()) {
      const bool advance_low =
          k + 1 == high.size() ||
          (i + 1 < low.size() && nodes[low[i + 1]].x() < nodes[high[k + 1]].x());
      if (advance_low) {
        triangles.push_back({low[i], low[i + 1], high[k]});
        ++i;
      } else {
        triangles.push_back({low[i], high[k + 1], high[k]});
        ++k;
      }
    }
  }
  return mesh_from(nodes, triangles);
}

MembraneMesh disc_mesh(double radius_mm, double element_size_mm, double jitter, std::uint64_t seed)
{
  check_size(2.0 * radius_mm, element_size_mm, "diameter");
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> shake(-jitter * element_size_mm, jitter * element_size_mm);
  std::vector<Vec2> nodes;
  const int boundary =
      std::max(8, static_cast<int>(std::lround(2.0 * M_PI * radius_mm / element_size_mm)));
  for (int i = 0; i < boundary; ++i) {
    const double angle = 2.0 * M_PI * i / boundary;
    nodes.emplace_back(radius_mm * std::cos(angle), radius_mm * std::sin(angle));
  }
  const double dy = element_size_mm * std::sqrt(3.0) / 2.0;
  const int half_rows = static_cast<int>(std::ceil(radius_mm / dy));
  const double inner = radius_mm - 0.6 * element_size_mm;
  for (int j = -half_rows; j <= half_rows; ++j) {
    const double offset = (j % 2 == 0) ? 0.0 : 0.5 * element_size_mm;
    const int half_columns = static_cast<int>(std::ceil(radius_mm / element_size_mm)) + 1;
    for (int i = -half_columns; i <= half_columns; ++i) {
      Vec2 p(i * element_size_mm + offset, j * dy);
      if (p.norm() > inner)
        continue;
      nodes.push_back(p + Vec2(shake(random), shake(random)));
    }
  }
  std::vector<Triangle> triangles = delaunay_triangulation(nodes);

  // Laplacian smoothing of the interior nodes (the boundary ones are the first `boundary`).
  std::vector<std::vector<int>> neighbours(nodes.size());
  for (const Triangle& t : triangles)
    for (int k = 0; k < 3; ++k) {
      neighbours[t[k]].push_back(t[(k + 1) % 3]);
      neighbours[t[k]].push_back(t[(k + 2) % 3]);
    }
  for (int sweep = 0; sweep < 3; ++sweep) {
    std::vector<Vec2> smoothed = nodes;
    for (std::size_t v = boundary; v < nodes.size(); ++v) {
      Vec2 sum = Vec2::Zero();
      for (int w : neighbours[v])
        sum += nodes[w];
      smoothed[v] = sum / static_cast<double>(neighbours[v].size());
    }
    const bool valid = std::all_of(triangles.begin(), triangles.end(), [&](const Triangle& t) {
      return signed_area(smoothed[t[0]], smoothed[t[1]], smoothed[t[2]]) > 0.0;
    });
    if (!valid)
      break;
    nodes.swap(smoothed);
  }
  return mesh_from(nodes, triangles);
}

} // namespace ligsim::membrane
