#include "stages/voxelize/voxelize.hpp"

#include "common/error.hpp"
#include "common/progress.hpp"
#include "stages/geometry/surface_query.hpp"
#include "stages/geometry/surface_topology.hpp"

#include <cmath>

namespace ligsim::voxelize {

double default_spacing(const TriangleSurface& surface)
{
  const double thickness = 2.0 * std::abs(signed_volume(surface)) / surface_area(surface);
  return thickness / 8.0;
}

namespace {

/// Marks column (i, j) from the sorted crossings `hits` (z values); false if they do not pair up.
bool fill_column(Mask& mask, int i, int j, const std::vector<double>& hits_z)
{
  if (hits_z.size() % 2 != 0)
    return false;
  for (std::size_t h = 0; h + 1 < hits_z.size(); h += 2) {
    const double z0 = hits_z[h], z1 = hits_z[h + 1];
    const int k0 = std::max(0, static_cast<int>(std::ceil((z0 - mask.origin.z()) / mask.spacing)));
    const int k1 = std::min(mask.dims.z() - 1,
                            static_cast<int>(std::floor((z1 - mask.origin.z()) / mask.spacing)));
    for (int k = k0; k <= k1; ++k)
      mask(i, j, k) = 1;
  }
  return true;
}

} // namespace

Mask voxelize(const SurfaceQuery& query, const Parameters& parameters)
{
  const TriangleSurface& surface = query.surface();
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
  Mask mask(dims, lo - (pad - 0.5) * spacing * Eigen::Vector3d::Ones(), spacing, 0);
  const double below = mask.origin.z() - spacing;
  Progress progress("voxelize", static_cast<std::size_t>(dims.y()));
  for (int j = 0; j < dims.y(); ++j) {
    for (int i = 0; i < dims.x(); ++i) {
      const Eigen::Vector3d centre = mask.point(i, j, 0);
      bool filled = false;
      // Offsets far below a voxel break ties with mesh vertices and edges lying exactly on the
      // column; the direction stays vertical to within 1e-9.
      for (int attempt = 1; attempt <= 4 && !filled; ++attempt) {
        const double jitter = 1e-7 * spacing * attempt;
        const Eigen::Vector3d origin(centre.x() + 0.7548776662 * jitter,
                                     centre.y() + 0.5698402910 * jitter, below);
        const Eigen::Vector3d direction(1e-9 * attempt, 2e-9 * attempt, 1.0);
        std::vector<double> hits = query.ray_hits(origin, direction);
        for (double& t : hits)
          t = origin.z() + t * direction.z();
        filled = fill_column(mask, i, j, hits);
      }
      if (!filled) // crossings never paired up: decide voxel by voxel
        for (int k = 0; k < dims.z(); ++k)
          mask(i, j, k) = query.inside(mask.point(i, j, k)) ? 1 : 0;
    }
    progress.advance();
  }
  progress.finish();
  return mask;
}

} // namespace ligsim::voxelize
