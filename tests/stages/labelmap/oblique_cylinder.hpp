#pragma once
/// @brief A test shape for label maps: a cylinder (radius 3 mm, length 16 mm) in an anisotropic
/// (0.3 x 0.3 x 1 mm), rotated and shifted image grid, its axis at about 30 degrees to the slice
/// planes (index axis k has the 1 mm spacing), so that the slices cut it in a staircase. Its
/// signed distance is known in closed form.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace ligsim::test {

struct ObliqueCylinder {
  static constexpr double radius_mm = 3.0, half_length_mm = 8.0;

  Eigen::Vector3i dims{72, 44, 20};
  Eigen::Vector3d spacing_mm{0.3, 0.3, 1.0};
  Eigen::Vector3d origin_mm{-40.0, 25.0, 110.0};
  Eigen::Matrix3d direction =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(-2, 1, 3).normalized()).toRotationMatrix();
  /// Physical (LPS) centre and unit axis, mm: the grid's centre, an oblique index direction.
  Eigen::Vector3d centre = physical(0.5 * (dims.cast<double>() - Eigen::Vector3d::Ones()));
  Eigen::Vector3d axis = direction * Eigen::Vector3d(1.0, 0.35, 0.62).normalized();

  /// The physical position of voxel index (i, j, k), mm.
  Eigen::Vector3d physical(const Eigen::Vector3d& ijk) const
  {
    return origin_mm + direction * spacing_mm.asDiagonal() * ijk;
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

  /// A voxel belongs to the cylinder if its centre does, as in a segmentation of a scan.
  bool voxel_inside(int i, int j, int k) const
  {
    return signed_distance(physical(Eigen::Vector3d(i, j, k))) <= 0.0;
  }

  double volume_mm3() const { return M_PI * radius_mm * radius_mm * 2.0 * half_length_mm; }
  double area_mm2() const { return 2.0 * M_PI * radius_mm * (2.0 * half_length_mm + radius_mm); }
};

} // namespace ligsim::test
