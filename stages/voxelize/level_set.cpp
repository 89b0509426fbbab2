#include "stages/voxelize/level_set.hpp"

#include "common/atomic_file.hpp"
#include "common/vdb_file_id.hpp"

#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>

#include <mutex>

namespace ligsim::vdb {

namespace {

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

void initialize_once()
{
  static std::once_flag flag;
  std::call_once(flag, [] { openvdb::initialize(); });
}

} // namespace

ScalarGrid level_set(const TriangleSurface& surface, const LevelSetRequest& request,
                     const std::filesystem::path& vdb_file)
{
  initialize_once();
  auto transform = openvdb::math::Transform::createLinearTransform(request.spacing_mm);
  transform->postTranslate(
      openvdb::Vec3d(request.origin.x(), request.origin.y(), request.origin.z()));
  const IndexSpaceMesh mesh(surface, request.origin, request.spacing_mm);
  // Exact distances to the triangles in the band: no renormalization (which would smooth them).
  const openvdb::FloatGrid::Ptr grid = openvdb::tools::meshToVolume<openvdb::FloatGrid>(
      mesh, *transform, static_cast<float>(request.exterior_band_voxels),
      static_cast<float>(request.interior_band_voxels), openvdb::tools::DISABLE_RENORMALIZATION);

  ScalarGrid sampled(request.dims, request.origin, request.spacing_mm, 0.0f);
  const auto accessor = grid->getConstAccessor();
  for (int k = 0; k < request.dims.z(); ++k)
    for (int j = 0; j < request.dims.y(); ++j)
      for (int i = 0; i < request.dims.x(); ++i)
        sampled(i, j, k) = accessor.getValue(openvdb::Coord(i, j, k));

  if (!vdb_file.empty()) {
    grid->setName("surface");
    grid->setGridClass(openvdb::GRID_LEVEL_SET);
    AtomicFile file(vdb_file);
    openvdb::io::File(file.temp_path().string()).write({grid});
    make_vdb_file_id_reproducible(file.temp_path());
    file.commit();
  }
  return sampled;
}

} // namespace ligsim::vdb
