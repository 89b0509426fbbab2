#pragma once
/// @brief Measures of one linear tetrahedron (v0, v1, v2, v3), positions in mm.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>

namespace ligsim::tetmesh {

inline constexpr double degrees_per_radian = 57.295779513082320876798;

/// (v1 - v0) . ((v2 - v0) x (v3 - v0)) / 6, mm^3: positive for a positively oriented tet.
inline double signed_tet_volume(const Eigen::Vector3d& v0, const Eigen::Vector3d& v1,
                                const Eigen::Vector3d& v2, const Eigen::Vector3d& v3)
{
  return (v1 - v0).dot((v2 - v0).cross(v3 - v0)) / 6.0;
}

/// The six interior dihedral angles, degrees, one per edge.
inline std::array<double, 6> dihedral_angles_deg(const std::array<Eigen::Vector3d, 4>& v)
{
  // Edge (i, j) with opposite vertices (k, l). The normals e x (vk - vi) and e x (vl - vi)
  // are the in-plane directions towards vk and vl turned by 90 degrees about e, so the
  // angle between them is the dihedral angle at e.
  static constexpr int edges[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2},
                                      {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}};
  std::array<double, 6> angles{};
  for (int e = 0; e < 6; ++e) {
    const auto [i, j, k, l] = edges[e];
    const Eigen::Vector3d edge = v[j] - v[i];
    const Eigen::Vector3d nk = edge.cross(v[k] - v[i]);
    const Eigen::Vector3d nl = edge.cross(v[l] - v[i]);
    angles[e] = std::atan2(nk.cross(nl).norm(), nk.dot(nl)) * degrees_per_radian;
  }
  return angles;
}

/// Circumradius / shortest edge: 0.612 for the regular tet, unbounded for slivers of caps.
inline double radius_edge_ratio(const std::array<Eigen::Vector3d, 4>& v)
{
  const Eigen::Vector3d a = v[1] - v[0], b = v[2] - v[0], c = v[3] - v[0];
  const Eigen::Vector3d centre_offset =
      (a.squaredNorm() * b.cross(c) + b.squaredNorm() * c.cross(a) + c.squaredNorm() * a.cross(b)) /
      (2.0 * a.dot(b.cross(c)));
  const double shortest = std::min({a.norm(), b.norm(), c.norm(), (v[2] - v[1]).norm(),
                                    (v[3] - v[1]).norm(), (v[3] - v[2]).norm()});
  return centre_offset.norm() / shortest;
}

/// Centre of the circle through a, b, c (in their plane), mm.
inline Eigen::Vector3d triangle_circumcentre(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                             const Eigen::Vector3d& c)
{
  const Eigen::Vector3d u = b - a, v = c - a, w = u.cross(v);
  return a +
         (u.squaredNorm() * v.cross(w) + v.squaredNorm() * w.cross(u)) / (2.0 * w.squaredNorm());
}

} // namespace ligsim::tetmesh
