#pragma once
/// @brief Surfaces for the tetmesh tests: an analytic capsule and the shipped MCL.

#include "common/mesh.hpp"

#include <filesystem>

namespace ligsim::tetmesh::test {

/// Closed, outward-oriented capsule: a cylinder of `radius` along +x from x = 0 to `length`,
/// with hemispherical caps; `segments` around the axis. Volume pi r^2 L + 4/3 pi r^3.
TriangleSurface capsule(double radius_mm, double length_mm, int segments);

/// A binary or ASCII STL read with VTK's vtkSTLReader (coincident points merged).
TriangleSurface read_stl(const std::filesystem::path& file);

} // namespace ligsim::tetmesh::test
