#include "stages/voxelize/voxelize.hpp"

#include "common/error.hpp"
#include "common/progress.hpp"
#include "stages/geometry/surface_topology.hpp"

#include <fmt/format.h>

#include <cmath>

namespace ligsim::voxelize {

namespace {

/// Voxel indices must fit an int per axis and the brick table (4 bytes per 512 voxels of the
/// box) must stay small next to the stored voxels.
constexpr double kMaxBoxVoxels = 2.0e11;

} // namespace

double default_spacing(const TriangleSurface& surface)
{
  const double thickness = 2.0 * std::abs(signed_volume(surface)) / surface_area(surface);
  return thickness / 8.0;
}

vdb::LevelSet level_set(const TriangleSurface& surface, const Parameters& parameters)
{
  const double spacing =
      parameters.spacing_mm > 0.0 ? parameters.spacing_mm : default_spacing(surface);
  if (!(spacing > 0.0) || !std::isfinite(spacing))
    fail("invalid voxel spacing {} mm", spacing);
  const Eigen::Vector3d lo = surface.V.colwise().minCoeff().transpose();
  const Eigen::Vector3d hi = surface.V.colwise().maxCoeff().transpose();
  const int pad = parameters.padding_voxels;
  const Eigen::Vector3d extent = (hi - lo) / spacing;
  const double box = (extent.array() + 2 * pad + 1).prod();
  const double inside = std::abs(signed_volume(surface)) / std::pow(spacing, 3);
  if (inside > parameters.max_voxels)
    fail("a {:.3f} mm voxel grid would hold {:.3g} voxels inside this surface (limit {:.3g}, "
         "[voxelize] max_voxels): choose a larger spacing",
         spacing, inside, parameters.max_voxels);
  if (box > kMaxBoxVoxels || extent.maxCoeff() > 1.0e9)
    fail("a {:.3f} mm voxel grid over this surface's bounding box would span {:.3g} voxels "
         "(limit {:.3g}): choose a larger spacing",
         spacing, box, kMaxBoxVoxels);
  const Eigen::Vector3i dims =
      extent.array().ceil().cast<int>().matrix() + Eigen::Vector3i::Constant(2 * pad + 1);

  // The bounding box's low corner falls half-way between voxel centres, not on them: a flat
  // face there (a cut end of a segmentation) would otherwise lie exactly on a layer of centres.
  vdb::LevelSetRequest request;
  request.dims = dims;
  request.origin = lo - (pad - 0.5) * spacing * Eigen::Vector3d::Ones();
  request.spacing_mm = spacing;
  log_info(fmt::format("voxelize: OpenVDB level set, {} x {} x {} voxels of {:.4f} mm "
                       "(about {:.3g} inside)",
                       dims.x(), dims.y(), dims.z(), spacing, inside));
  return vdb::LevelSet::of_surface(surface, request);
}

Mask voxelize(const TriangleSurface& surface, const Parameters& parameters,
              const std::filesystem::path& vdb_file)
{
  const vdb::LevelSet levels = level_set(surface, parameters);
  if (!vdb_file.empty())
    levels.write(vdb_file);
  return levels.inside();
}

} // namespace ligsim::voxelize
