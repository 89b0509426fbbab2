#pragma once
/// @brief The generalized winding number of a triangle surface (Jacobson, Kavan and
/// Sorkine-Hornung 2013): the solid angle the triangles subtend at a point over 4 pi. 1 inside a
/// closed surface with outward triangles, -1 inside one with inward triangles, 0 outside; it
/// degrades gracefully on small holes and flipped patches, and sums over separate shells.
/// Evaluated on a bounding-volume hierarchy whose far clusters are a Taylor expansion about their
/// centre (Barill et al. 2018; the dipole and its first-order term), so a query costs about
/// log(#F) clusters, not #F triangles.

#include "common/mesh.hpp"

#include <Eigen/Geometry>

#include <vector>

namespace ligsim::sim {

class WindingNumber {
public:
  /// Builds the hierarchy over `surface` (mm; kept by value). A cluster is approximated from
  /// points farther than `accuracy` times its radius from its centre (larger: closer to exact,
  /// slower).
  explicit WindingNumber(const TriangleSurface& surface, double accuracy = 2.0);

  /// w(p), hierarchical.
  double operator()(const Eigen::Vector3d& p) const;
  /// w(p) summed over every triangle: the reference.
  double exact(const Eigen::Vector3d& p) const;
  /// The box around the triangles, mm: outside it w is small (0 for a closed surface).
  const Eigen::AlignedBox3d& bounds() const { return m_bounds; }

private:
  struct Node {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero(); ///< area-weighted centroid, mm
    Eigen::Vector3d dipole = Eigen::Vector3d::Zero(); ///< sum of area vectors a, mm^2
    Eigen::Matrix3d moment = Eigen::Matrix3d::Zero(); ///< sum of a (centroid - centre)^T, mm^3
    double radius = 0.0;                              ///< of the ball around `centre`, mm
    int first = 0, count = 0;                         ///< its triangles: m_order[first...]
    int left = -1, right = -1;                        ///< children; -1: a leaf
  };
  int build(int first, int count);
  double triangle_solid_angle(int f, const Eigen::Vector3d& p) const;

  TriangleSurface m_surface;
  double m_accuracy;
  std::vector<int> m_order; ///< triangle indices, grouped by node
  std::vector<Node> m_nodes;
  Eigen::AlignedBox3d m_bounds;
};

} // namespace ligsim::sim
