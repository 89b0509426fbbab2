#include "tests/stages/tetmesh/test_surfaces.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace ligsim::tetmesh::test {

TriangleSurface capsule(double radius_mm, double length_mm, int segments)
{
  // Profile (x, rho) from the left pole to the right pole; rings of `segments` vertices
  // between the poles. Cap rings every 90 / (segments / 4) degrees, cylinder rings spaced
  // about as far apart as the points around.
  const double pi = std::acos(-1.0);
  const int cap_rings = segments / 4;
  const int length_rings =
      std::max(1, static_cast<int>(std::lround(length_mm / (2 * pi * radius_mm / segments))));
  std::vector<std::pair<double, double>> profile;
  for (int i = 0; i <= cap_rings; ++i) {
    const double angle = pi - 0.5 * pi * i / cap_rings; // pi (left pole) .. pi/2
    profile.emplace_back(radius_mm * std::cos(angle), radius_mm * std::sin(angle));
  }
  for (int i = 1; i < length_rings; ++i)
    profile.emplace_back(length_mm * i / length_rings, radius_mm);
  for (int i = 0; i <= cap_rings; ++i) {
    const double angle = 0.5 * pi - 0.5 * pi * i / cap_rings; // pi/2 .. 0 (right pole)
    profile.emplace_back(length_mm + radius_mm * std::cos(angle), radius_mm * std::sin(angle));
  }

  const int rings = static_cast<int>(profile.size()) - 2; // without the poles
  TriangleSurface surface;
  surface.V.resize(2 + rings * segments, 3);
  surface.V.row(0) << profile.front().first, 0, 0;
  for (int r = 0; r < rings; ++r)
    for (int j = 0; j < segments; ++j) {
      const double phi = 2 * pi * j / segments;
      const auto [x, rho] = profile[static_cast<std::size_t>(r + 1)];
      surface.V.row(1 + r * segments + j) << x, rho * std::cos(phi), rho * std::sin(phi);
    }
  const int last_pole = 1 + rings * segments;
  surface.V.row(last_pole) << profile.back().first, 0, 0;

  // Outward: a step along phi then a step along +x turns e_phi x e_x = e_rho.
  const auto ring_vertex = [&](int r, int j) { return 1 + r * segments + (j % segments); };
  std::vector<Eigen::Vector3i> faces;
  for (int j = 0; j < segments; ++j) {
    faces.emplace_back(0, ring_vertex(0, j + 1), ring_vertex(0, j));
    for (int r = 0; r + 1 < rings; ++r) {
      faces.emplace_back(ring_vertex(r, j), ring_vertex(r, j + 1), ring_vertex(r + 1, j));
      faces.emplace_back(ring_vertex(r, j + 1), ring_vertex(r + 1, j + 1), ring_vertex(r + 1, j));
    }
    faces.emplace_back(ring_vertex(rings - 1, j), ring_vertex(rings - 1, j + 1), last_pole);
  }
  surface.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    surface.F.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
  return surface;
}

} // namespace ligsim::tetmesh::test
