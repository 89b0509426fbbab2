#include "stages/voxelize/level_set.hpp"

#include "common/error.hpp"
#include "stages/geometry/grid_vdb_detail.hpp"

#include <openvdb/tools/MeshToVolume.h>

#include <limits>

namespace ligsim::vdb {

namespace {

constexpr const char* kGridName = "surface";

/// The surface in OpenVDB's index space (voxel centres at integer coordinates).
class IndexSpaceMesh {
public:
  IndexSpaceMesh(const TriangleSurface& surface, const Eigen::Vector3d& origin, double spacing)
      : m_surface(surface)
      , m_origin(origin)
      , m_spacing(spacing)
  {
  }
  std::size_t polygonCount() const { return static_cast<std::size_t>(m_surface.F.rows()); }
  std::size_t pointCount() const { return static_cast<std::size_t>(m_surface.V.rows()); }
  std::size_t vertexCount(std::size_t) const { return 3; }
  void getIndexSpacePoint(std::size_t n, std::size_t v, openvdb::Vec3d& pos) const
  {
    const Eigen::Vector3d p =
        (m_surface.V.row(m_surface.F(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(v)))
             .transpose() -
         m_origin) /
        m_spacing;
    pos = openvdb::Vec3d(p.x(), p.y(), p.z());
  }

private:
  const TriangleSurface& m_surface;
  Eigen::Vector3d m_origin;
  double m_spacing;
};

} // namespace

struct LevelSet::Impl {
  openvdb::FloatGrid::Ptr grid;
  Eigen::Vector3i dims;
};

LevelSet::LevelSet(std::shared_ptr<const Impl> impl)
    : m_impl(std::move(impl))
{
}

LevelSet LevelSet::of_surface(const TriangleSurface& surface, const LevelSetRequest& request)
{
  detail::initialize();
  const auto transform = detail::transform_of(request.origin, request.spacing_mm);
  const IndexSpaceMesh mesh(surface, request.origin, request.spacing_mm);
  // Interior filled (distances all the way in); no renormalization, which would smooth the
  // distances to the triangles.
  auto grid = openvdb::tools::meshToVolume<openvdb::FloatGrid>(
      mesh, *transform, static_cast<float>(request.exterior_band_voxels),
      std::numeric_limits<float>::max(), openvdb::tools::DISABLE_RENORMALIZATION);
  // meshToVolume gives the grid a transform whose scale reads back rounded far from the
  // origin; the index space is the same, so set ours.
  grid->setTransform(transform);
  grid->setName(kGridName);
  grid->setGridClass(openvdb::GRID_LEVEL_SET);
  detail::set_dims(*grid, request.dims);
  return LevelSet(std::make_shared<const Impl>(Impl{grid, request.dims}));
}

LevelSet LevelSet::read(const std::filesystem::path& file)
{
  auto grid = detail::read_float_grid(file, kGridName);
  const Eigen::Vector3i dims = detail::dims_of(*grid, file);
  return LevelSet(std::make_shared<const Impl>(Impl{grid, dims}));
}

void LevelSet::write(const std::filesystem::path& file) const
{
  detail::write_grids(file, {m_impl->grid});
}

Eigen::Vector3i LevelSet::dims() const
{
  return m_impl->dims;
}

double LevelSet::spacing_mm() const
{
  return detail::spacing_of(m_impl->grid->transform());
}

Mask LevelSet::inside() const
{
  return detail::from_vdb(*m_impl->grid, m_impl->dims, std::uint8_t{0},
                          [](float v) { return static_cast<std::uint8_t>(v < 0.0f ? 1 : 0); });
}

ScalarGrid LevelSet::signed_distance(double outside_limit_mm) const
{
  const auto limit = static_cast<float>(outside_limit_mm);
  return detail::from_vdb(*m_impl->grid, m_impl->dims, -limit,
                          [limit](float v) { return v < limit ? -v : -limit; });
}

double LevelSet::exterior_band_voxels() const
{
  // meshToVolume sets the background (the value beyond the band) to the band's width, mm.
  return static_cast<double>(m_impl->grid->background()) / spacing_mm();
}

std::size_t LevelSet::active_voxels() const
{
  return static_cast<std::size_t>(m_impl->grid->activeVoxelCount());
}

} // namespace ligsim::vdb
