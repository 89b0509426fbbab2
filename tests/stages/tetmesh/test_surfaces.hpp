#pragma once
/// @brief An analytic capsule for the tetmesh tests: smooth (no sharp edges) and ligament-like.

#include "common/mesh.hpp"

namespace ligsim::tetmesh::test {

/// Closed, outward-oriented capsule: a cylinder of `radius` along +x from x = 0 to `length`,
/// with hemispherical caps; `segments` around the axis. Volume pi r^2 L + 4/3 pi r^3.
TriangleSurface capsule(double radius_mm, double length_mm, int segments);

} // namespace ligsim::tetmesh::test
