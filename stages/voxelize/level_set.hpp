#pragma once
/// @brief The signed-distance level set of a triangle surface through OpenVDB (the
/// translation unit that computes it), on the voxel box of our grids: the source of the
/// voxelize stage's mask and of the distance stage's distances, and a .vdb file for Houdini
/// and Blender.

#include "common/mesh.hpp"
#include "stages/geometry/grid.hpp"

#include <filesystem>
#include <memory>

namespace ligsim::vdb {

/// Where the level set is computed.
struct LevelSetRequest {
  Eigen::Vector3i dims = Eigen::Vector3i::Zero();
  Eigen::Vector3d origin = Eigen::Vector3d::Zero(); ///< centre of voxel (0, 0, 0), mm
  double spacing_mm = 1.0;
  double exterior_band_voxels = 3.0; ///< exact distances this far outside
};

/// OpenVDB's meshToVolume with the interior filled and without renormalization (which would
/// smooth the distances): distances to the triangles in the exterior band and inside, found by
/// passing the closest triangle from voxel to voxel (exact to that triangle; about 1 % of the
/// voxels, near folds and corners, get a farther one: distance::signed_distance() recomputes
/// them). Its sign comes from a flood fill of the outside, so it is not fooled by non-manifold
/// edges, self-intersections, overlapping shells or flipped triangles (which break ray parity).
/// Storage is sparse: memory grows with the shape's volume, not its bounding box.
class LevelSet {
public:
  static LevelSet of_surface(const TriangleSurface& surface, const LevelSetRequest& request);
  /// A level set written by write(); throws InputError naming the file if unreadable.
  static LevelSet read(const std::filesystem::path& file);
  /// Writes the level set (atomically) as the grid "surface", class level set.
  void write(const std::filesystem::path& file) const;

  Eigen::Vector3i dims() const;
  double spacing_mm() const;
  /// Width of the exterior band, voxels (its outside voxels farther away are not stored).
  double exterior_band_voxels() const;
  /// 1 at the voxel centres inside (negative level set).
  Mask inside() const;
  /// The level set's distances in our convention, mm: positive inside, negative outside;
  /// outside voxels at least `outside_limit_mm` away hold -outside_limit_mm.
  ScalarGrid signed_distance(double outside_limit_mm) const;
  /// Voxels holding a value (the inside and the exterior band).
  std::size_t active_voxels() const;

private:
  struct Impl;
  explicit LevelSet(std::shared_ptr<const Impl> impl);
  std::shared_ptr<const Impl> m_impl;
};

} // namespace ligsim::vdb
