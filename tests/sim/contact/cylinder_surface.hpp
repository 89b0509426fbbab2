#pragma once
/// A closed triangulated cylinder (capped) for the contact tests.

#include "common/mesh.hpp"

#include <cmath>

namespace ligsim::sim::test {

/// Axis along y through the origin, y in [-half_length, half_length], `segments` around.
inline TriangleSurface cylinder_surface(double radius, double half_length, int segments)
{
  TriangleSurface s;
  s.V.resize(2 * segments + 2, 3);
  for (int i = 0; i < segments; ++i) {
    const double a = 2.0 * M_PI * i / segments;
    s.V.row(i) << radius * std::cos(a), -half_length, radius * std::sin(a);
    s.V.row(segments + i) << radius * std::cos(a), half_length, radius * std::sin(a);
  }
  s.V.row(2 * segments) << 0, -half_length, 0;
  s.V.row(2 * segments + 1) << 0, half_length, 0;
  s.F.resize(4 * segments, 3);
  for (int i = 0; i < segments; ++i) {
    const int j = (i + 1) % segments;
    s.F.row(4 * i) << i, j, segments + i;
    s.F.row(4 * i + 1) << j, segments + j, segments + i;
    s.F.row(4 * i + 2) << 2 * segments, j, i;
    s.F.row(4 * i + 3) << 2 * segments + 1, segments + i, segments + j;
  }
  return s;
}

} // namespace ligsim::sim::test
