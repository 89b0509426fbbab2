#pragma once
/// @brief Procedural meshes for the tearing scenes. Both are near-equilateral triangles from a
/// jittered triangular lattice, so no edge direction is favoured by the mesh (the lattice's
/// edges run at 0, 60 and 120 degrees, the jitter breaks their alignment).

#include "sim/membrane/mesh/membrane_mesh.hpp"

#include <cstdint>

namespace ligsim::membrane {

/// Rectangle [-width/2, width/2] x [-height/2, height/2]: rows of a triangular lattice with
/// spacing about `element_size_mm`, triangulated strip by strip; interior nodes moved by up to
/// `jitter` x element size in x and y (seeded), except next to the sides. About
/// 2.31 (width x height) / size^2 triangles.
MembraneMesh rectangle_mesh(double width_mm, double height_mm, double element_size_mm,
                            double jitter, std::uint64_t seed);

/// Disc of radius `radius_mm` around the origin: boundary nodes spaced about `element_size_mm`
/// on the circle, a jittered triangular lattice inside, Delaunay triangles, then three sweeps of
/// Laplacian smoothing of the interior nodes.
MembraneMesh disc_mesh(double radius_mm, double element_size_mm, double jitter, std::uint64_t seed);

} // namespace ligsim::membrane
