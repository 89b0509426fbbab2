#pragma once
/// @brief A closed triangulated sphere (a subdivided icosahedron, outward faces): a rigid
/// obstacle with a known distance for contact tests and verification.

#include "common/mesh.hpp"

namespace ligsim::sim {

/// 20 * 4^levels triangles on the sphere of `radius_mm` about `centre_mm`.
TriangleSurface sphere_surface(const Eigen::Vector3d& centre_mm, double radius_mm, int levels);

} // namespace ligsim::sim
