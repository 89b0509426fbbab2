#pragma once
/// @brief Test shapes for label maps, known in closed form: a cylinder and a thin band in an
/// anisotropic (0.3 x 0.3 x 1 mm), rotated and shifted image grid, oblique to the slice planes
/// (index axis k has the 1 mm spacing), so that the slices cut them in a staircase.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace ligsim::test {

/// The image grid: index (i, j, k) lies at origin + direction * diag(spacing) * (i, j, k).
struct ObliqueGrid {
  Eigen::Vector3i dims;
  Eigen::Vector3d spacing_mm{0.3, 0.3, 1.0};
  Eigen::Vector3d origin_mm{-40.0, 25.0, 110.0};
  Eigen::Matrix3d direction =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(-2, 1, 3).normalized()).toRotationMatrix();

  explicit ObliqueGrid(const Eigen::Vector3i& grid_dims)
      : dims(grid_dims)
  {
  }

  /// The physical (LPS) position of voxel index (i, j, k), mm.
  Eigen::Vector3d physical(const Eigen::Vector3d& ijk) const
  {
    return origin_mm + direction * spacing_mm.asDiagonal() * ijk;
  }
  Eigen::Vector3d grid_centre() const
  {
    return physical(0.5 * (dims.cast<double>() - Eigen::Vector3d::Ones()));
  }
};

/// A cylinder of radius 3 mm and length 16 mm centred in the grid, its axis at about 30
/// degrees to the slices.
struct ObliqueCylinder : ObliqueGrid {
  static constexpr double radius_mm = 3.0, half_length_mm = 8.0;
  Eigen::Vector3d centre = grid_centre();
  Eigen::Vector3d axis = direction * Eigen::Vector3d(1.0, 0.35, 0.62).normalized();

  ObliqueCylinder()
      : ObliqueGrid({72, 44, 20})
  {
  }

  /// Signed distance to the finite cylinder (negative inside), mm.
  double signed_distance(const Eigen::Vector3d& p) const
  {
    const Eigen::Vector3d d = p - centre;
    const double along = d.dot(axis);
    const double radial = (d - along * axis).norm() - radius_mm;
    const double axial = std::abs(along) - half_length_mm;
    const double outside = std::hypot(std::max(radial, 0.0), std::max(axial, 0.0));
    return outside + std::min(std::max(radial, axial), 0.0);
  }
  /// Distance to the nearer of the two circular rims, mm.
  double edge_distance(const Eigen::Vector3d& p) const
  {
    const Eigen::Vector3d d = p - centre;
    const double along = d.dot(axis);
    return std::hypot((d - along * axis).norm() - radius_mm, std::abs(along) - half_length_mm);
  }
  double volume_mm3() const { return M_PI * radius_mm * radius_mm * 2.0 * half_length_mm; }
  double area_mm2() const { return 2.0 * M_PI * radius_mm * (2.0 * half_length_mm + radius_mm); }
};

/// A band of 20 x 6 x 1.5 mm (a ligament's proportions: 1.5 slices thick) centred in the grid,
/// its plane tilted by 17 degrees to the slices.
struct ObliqueBand : ObliqueGrid {
  Eigen::Vector3d half_size_mm{10.0, 3.0, 0.75};
  Eigen::Vector3d centre = grid_centre();
  /// Columns: the band's length, width and thickness directions (physical).
  Eigen::Matrix3d axes =
      direction *
      Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 0.3, 0).normalized()).toRotationMatrix() *
      Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()).toRotationMatrix();

  ObliqueBand()
      : ObliqueGrid({90, 90, 30})
  {
  }

  /// Per axis: distance beyond the half size (negative inside), mm.
  Eigen::Vector3d excess(const Eigen::Vector3d& p) const
  {
    return (axes.transpose() * (p - centre)).cwiseAbs() - half_size_mm;
  }
  /// Signed distance to the box (negative inside), mm.
  double signed_distance(const Eigen::Vector3d& p) const
  {
    const Eigen::Vector3d q = excess(p);
    return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
  }
  /// Distance to the nearest of the box's twelve edges, mm.
  double edge_distance(const Eigen::Vector3d& p) const
  {
    const Eigen::Vector3d q = excess(p);
    double nearest = 1e300;
    for (int a = 0; a < 3; ++a) // the edges along axis a
      nearest = std::min(
          nearest, Eigen::Vector3d(q[(a + 1) % 3], q[(a + 2) % 3], std::max(q[a], 0.0)).norm());
    return nearest;
  }
  double volume_mm3() const { return 8.0 * half_size_mm.prod(); }
  double area_mm2() const
  {
    const Eigen::Vector3d s = 2.0 * half_size_mm;
    return 2.0 * (s.x() * s.y() + s.y() * s.z() + s.z() * s.x());
  }
};

/// A voxel belongs to the shape if its centre does, as in a segmentation of a scan.
template <class Shape> bool voxel_inside(const Shape& shape, int i, int j, int k)
{
  return shape.signed_distance(shape.physical(Eigen::Vector3d(i, j, k))) <= 0.0;
}

} // namespace ligsim::test
