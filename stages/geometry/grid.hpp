#pragma once
/// @brief A regular voxel grid with isotropic spacing: the images of the model-building stages.

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace ligsim {

/// Values at voxel centres; voxel (i, j, k) sits at origin + spacing * (i, j, k), mm.
/// Storage is x-fastest, as in VTK's image data.
template <class T> struct Grid {
  Eigen::Vector3i dims = Eigen::Vector3i::Zero();
  Eigen::Vector3d origin = Eigen::Vector3d::Zero(); ///< centre of voxel (0, 0, 0), mm
  double spacing = 1.0;                             ///< voxel edge, mm
  std::vector<T> values;

  Grid() = default;
  Grid(const Eigen::Vector3i& dims_, const Eigen::Vector3d& origin_, double spacing_, T fill = T{})
      : dims(dims_)
      , origin(origin_)
      , spacing(spacing_)
      , values(voxel_count(), fill)
  {
  }

  /// Same geometry as `other`, new values.
  template <class U> static Grid like(const Grid<U>& other, T fill = T{})
  {
    return Grid(other.dims, other.origin, other.spacing, fill);
  }

  std::size_t voxel_count() const
  {
    return static_cast<std::size_t>(dims.x()) * dims.y() * dims.z();
  }
  std::size_t index(int i, int j, int k) const
  {
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(dims.x()) * (j + static_cast<std::size_t>(dims.y()) * k);
  }
  Eigen::Vector3i ijk(std::size_t index) const
  {
    const auto nx = static_cast<std::size_t>(dims.x());
    const auto ny = static_cast<std::size_t>(dims.y());
    return {static_cast<int>(index % nx), static_cast<int>((index / nx) % ny),
            static_cast<int>(index / (nx * ny))};
  }
  bool contains(int i, int j, int k) const
  {
    return i >= 0 && j >= 0 && k >= 0 && i < dims.x() && j < dims.y() && k < dims.z();
  }
  Eigen::Vector3d point(int i, int j, int k) const
  {
    return origin + spacing * Eigen::Vector3d(i, j, k);
  }
  Eigen::Vector3d point(std::size_t index) const { return point_of(ijk(index)); }
  Eigen::Vector3d point_of(const Eigen::Vector3i& v) const { return point(v.x(), v.y(), v.z()); }
  /// Continuous voxel coordinates of a point (voxel centres at integers).
  Eigen::Vector3d voxel_coordinates(const Eigen::Vector3d& p) const
  {
    return (p - origin) / spacing;
  }

  T& operator()(int i, int j, int k) { return values[index(i, j, k)]; }
  const T& operator()(int i, int j, int k) const { return values[index(i, j, k)]; }
};

using Mask = Grid<std::uint8_t>; ///< 1 inside the surface, 0 outside
using ScalarGrid = Grid<float>;

/// The 26 neighbour offsets of a voxel.
const std::vector<Eigen::Vector3i>& neighbourhood_26();

} // namespace ligsim
