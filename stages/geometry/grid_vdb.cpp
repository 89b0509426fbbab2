#include "stages/geometry/grid_vdb.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/vdb_file_id.hpp"
#include "stages/geometry/grid_vdb_detail.hpp"

#include <mutex>

namespace ligsim::vdb {

namespace detail {

namespace {
constexpr const char* kDimsKey = "ligsim_box_dims";
}

void initialize()
{
  static std::once_flag flag;
  std::call_once(flag, [] { openvdb::initialize(); });
}

openvdb::math::Transform::Ptr transform_of(const Eigen::Vector3d& origin, double spacing)
{
  auto transform = openvdb::math::Transform::createLinearTransform(spacing);
  transform->postTranslate(openvdb::Vec3d(origin.x(), origin.y(), origin.z()));
  return transform;
}

double spacing_of(const openvdb::math::Transform& transform)
{
  // The scale as stored. voxelSize() maps unit vectors and measures them, which rounds (0.05
  // comes back as 0.0499999999999545): every voxel centre and distance would move by that.
  return transform.baseMap()->getAffineMap()->getMat4()(0, 0);
}

void set_dims(openvdb::GridBase& grid, const Eigen::Vector3i& dims)
{
  grid.insertMeta(kDimsKey, openvdb::Vec3IMetadata(openvdb::Vec3i(dims.x(), dims.y(), dims.z())));
}

Eigen::Vector3i dims_of(const openvdb::GridBase& grid, const std::filesystem::path& file)
{
  const auto meta = grid.getMetadata<openvdb::Vec3IMetadata>(kDimsKey);
  if (!meta)
    fail("'{}' has no '{}' metadata: not written by ligsim", file.string(), kDimsKey);
  const openvdb::Vec3i d = meta->value();
  return {d.x(), d.y(), d.z()};
}

openvdb::FloatGrid::Ptr to_vdb(const ScalarGrid& grid, const std::string& name)
{
  initialize();
  auto result = openvdb::FloatGrid::create(grid.background());
  result->setTransform(transform_of(grid.origin, grid.spacing));
  result->setName(name);
  set_dims(*result, grid.dims);
  auto& tree = result->tree();
  for (std::size_t b = 0; b < grid.brick_count(); ++b) {
    const Eigen::Vector3i o = grid.brick_origin(b);
    auto* leaf = tree.touchLeaf(openvdb::Coord(o.x(), o.y(), o.z()));
    grid.for_each_in_brick(b, [&](const Eigen::Vector3i& v, float value) {
      const auto n = leaf->coordToOffset(openvdb::Coord(v.x(), v.y(), v.z()));
      if (value == grid.background())
        leaf->setValueOff(n, value);
      else
        leaf->setValueOn(n, value);
    });
  }
  return result;
}

openvdb::FloatGrid::Ptr read_float_grid(const std::filesystem::path& file, const std::string& name)
{
  initialize();
  if (!std::filesystem::exists(file))
    fail("cannot read '{}': no such file", file.string());
  openvdb::GridBase::Ptr base;
  try {
    openvdb::io::File vdb_file(file.string());
    vdb_file.open();
    if (vdb_file.hasGrid(name))
      base = vdb_file.readGrid(name);
    vdb_file.close();
  } catch (const openvdb::Exception& e) {
    fail("cannot read '{}': {}", file.string(), e.what());
  }
  if (!base)
    fail("'{}' holds no grid named '{}'", file.string(), name);
  auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
  if (!grid)
    fail("grid '{}' in '{}' is not a float grid", name, file.string());
  return grid;
}

void write_grids(const std::filesystem::path& file, const openvdb::GridPtrVec& grids)
{
  initialize();
  AtomicFile atomic(file);
  openvdb::io::File(atomic.temp_path().string()).write(grids);
  make_vdb_file_id_reproducible(atomic.temp_path());
  atomic.commit();
}

} // namespace detail

void write_grid(const ScalarGrid& grid, const std::string& name, const std::filesystem::path& file)
{
  detail::write_grids(file, {detail::to_vdb(grid, name)});
}

ScalarGrid read_grid(const std::filesystem::path& file, const std::string& name)
{
  const auto vdb_grid = detail::read_float_grid(file, name);
  return detail::from_vdb(*vdb_grid, detail::dims_of(*vdb_grid, file), vdb_grid->background(),
                          [](float v) { return v; });
}

} // namespace ligsim::vdb
