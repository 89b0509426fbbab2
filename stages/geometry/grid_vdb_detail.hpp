#pragma once
/// @brief Conversions between our sparse grids and OpenVDB float grids. Includes OpenVDB:
/// only for the few translation units that talk to it (grid_vdb.cpp, level_set.cpp).

#include "stages/geometry/grid.hpp"

#include <openvdb/openvdb.h>

#include <filesystem>

namespace ligsim::vdb::detail {

/// OpenVDB initialised once per process.
void initialize();

/// Index space (i, j, k) of our grid to world space, mm.
openvdb::math::Transform::Ptr transform_of(const Eigen::Vector3d& origin, double spacing);

/// The voxel spacing (mm) that transform_of() was given, exactly.
double spacing_of(const openvdb::math::Transform& transform);

/// The stored bricks of `grid` as leaves (voxels other than the background active), with the
/// grid's box recorded as metadata, so from_vdb() restores the same geometry.
openvdb::FloatGrid::Ptr to_vdb(const ScalarGrid& grid, const std::string& name);

/// The box dims recorded by to_vdb() (or by the level set).
void set_dims(openvdb::GridBase& grid, const Eigen::Vector3i& dims);
Eigen::Vector3i dims_of(const openvdb::GridBase& grid, const std::filesystem::path& file);

/// The first grid named `name` in a .vdb file, as a float grid; throws InputError naming the
/// file if it is missing or of another type.
openvdb::FloatGrid::Ptr read_float_grid(const std::filesystem::path& file, const std::string& name);
/// Writes `grids` atomically.
void write_grids(const std::filesystem::path& file, const openvdb::GridPtrVec& grids);

/// Our grid over the box `dims` from an OpenVDB grid in the same index space: each voxel's value
/// v becomes map(v); a brick is stored only where some map(v) differs from `background`.
/// Tiles (constant regions above the leaves) are expanded voxel by voxel.
template <class T, class Map>
Grid<T> from_vdb(const openvdb::FloatGrid& vdb_grid, const Eigen::Vector3i& dims, T background,
                 Map&& map)
{
  const openvdb::Vec3d o = vdb_grid.transform().indexToWorld(openvdb::Vec3d(0.0, 0.0, 0.0));
  Grid<T> grid(dims, {o.x(), o.y(), o.z()}, spacing_of(vdb_grid.transform()), background);
  using Leaf = openvdb::FloatTree::LeafNodeType;
  static_assert(Leaf::DIM == Grid<T>::kBrickEdge, "bricks and leaves must line up");
  auto in_box = [&](const openvdb::Coord& c) { return grid.contains(c.x(), c.y(), c.z()); };
  grid.reserve_bricks(vdb_grid.tree().leafCount());
  for (auto leaf = vdb_grid.tree().cbeginLeaf(); leaf; ++leaf) {
    bool any = false;
    for (openvdb::Index n = 0; n < Leaf::SIZE && !any; ++n)
      any = in_box(leaf->offsetToGlobalCoord(n)) && !(map(leaf->getValue(n)) == background);
    if (!any)
      continue;
    for (openvdb::Index n = 0; n < Leaf::SIZE; ++n) {
      const openvdb::Coord c = leaf->offsetToGlobalCoord(n);
      if (in_box(c))
        grid.set(c.x(), c.y(), c.z(), map(leaf->getValue(n)));
    }
  }
  auto tile = vdb_grid.tree().cbeginValueAll();
  tile.setMaxDepth(openvdb::FloatTree::ValueAllCIter::LEAF_DEPTH - 1);
  for (; tile; ++tile) {
    const T value = map(*tile);
    if (value == background)
      continue;
    openvdb::CoordBBox box;
    tile.getBoundingBox(box);
    box.intersect(openvdb::CoordBBox(openvdb::Coord(0, 0, 0),
                                     openvdb::Coord(dims.x() - 1, dims.y() - 1, dims.z() - 1)));
    for (auto c = box.begin(); c; ++c)
      grid.set((*c).x(), (*c).y(), (*c).z(), value);
  }
  return grid;
}

} // namespace ligsim::vdb::detail
