#include "stages/voxelize/voxelize.hpp"

#include "common/error.hpp"
#include "common/progress.hpp"
#include "stages/geometry/surface_topology.hpp"
#include "stages/voxelize/level_set.hpp"

#include <fmt/format.h>

#include <cmath>

namespace ligsim::voxelize {

double default_spacing(const TriangleSurface& surface)
{
  const double thickness = 2.0 * std::abs(signed_volume(surface)) / surface_area(surface);
  return thickness / 8.0;
}

Mask voxelize(const TriangleSurface& surface, const Parameters& parameters,
              const std::filesystem::path& vdb_file)
{
  const double spacing =
      parameters.spacing_mm > 0.0 ? parameters.spacing_mm : default_spacing(surface);
  if (!(spacing > 0.0) || !std::isfinite(spacing))
    fail("invalid voxel spacing {} mm", spacing);
  const Eigen::Vector3d lo = surface.V.colwise().minCoeff().transpose();
  const Eigen::Vector3d hi = surface.V.colwise().maxCoeff().transpose();
  const int pad = parameters.padding_voxels;
  const Eigen::Vector3i dims = ((hi - lo) / spacing).array().ceil().cast<int>().matrix() +
                               Eigen::Vector3i::Constant(2 * pad + 1);
  const double count = static_cast<double>(dims.x()) * dims.y() * dims.z();
  if (count > parameters.max_voxels)
    fail("a {:.3f} mm voxel grid over this surface would hold {:.3g} voxels (limit {:.3g}): "
         "choose a larger spacing",
         spacing, count, parameters.max_voxels);

  // The bounding box's low corner falls half-way between voxel centres, not on them: a flat
  // face there (a cut end of a segmentation) would otherwise lie exactly on a layer of centres.
  vdb::LevelSetRequest request;
  request.dims = dims;
  request.origin = lo - (pad - 0.5) * spacing * Eigen::Vector3d::Ones();
  request.spacing_mm = spacing;
  log_info(fmt::format("voxelize: OpenVDB level set, {} x {} x {} voxels of {:.4f} mm", dims.x(),
                       dims.y(), dims.z(), spacing));
  const ScalarGrid level = vdb::level_set(surface, request, vdb_file);
  Mask mask = Mask::like(level, 0);
  for (std::size_t v = 0; v < level.values.size(); ++v)
    mask.values[v] = level.values[v] < 0.0f ? 1 : 0;
  return mask;
}

} // namespace ligsim::voxelize
