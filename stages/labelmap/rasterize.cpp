#include "stages/labelmap/rasterize.hpp"

#include "common/error.hpp"
#include "common/progress.hpp"
#include "stages/geometry/surface_query.hpp"

#include <cmath>

namespace ligsim::labelmap {

LabelImage rasterize(const std::vector<LabeledSurface>& parts, const Eigen::Vector3d& lo,
                     const Eigen::Vector3d& hi, const Eigen::Vector3d& spacing_mm)
{
  if ((spacing_mm.array() <= 0.0).any() || !spacing_mm.allFinite())
    fail("invalid voxel spacing ({}, {}, {}) mm", spacing_mm.x(), spacing_mm.y(), spacing_mm.z());
  LabelImage image;
  image.spacing_mm = spacing_mm;
  image.origin_mm = lo + 0.5 * spacing_mm;
  image.dims = ((hi - lo).array() / spacing_mm.array()).ceil().cast<int>().max(1).matrix();
  image.labels.assign(static_cast<std::size_t>(image.dims.prod()), 0);
  image.frame_from_surfaces = true;

  Progress progress("labelmap", parts.size());
  for (const LabeledSurface& part : parts) {
    const SurfaceQuery query(part.surface);
    for (int j = 0; j < image.dims.y(); ++j)
      for (int i = 0; i < image.dims.x(); ++i) {
        const Eigen::Vector3d centre = image.physical_point(Eigen::Vector3d(i, j, 0));
        // A tiny tilt keeps the ray off mesh edges and vertices lying exactly on the column.
        const Eigen::Vector3d origin(centre.x() + 1e-7, centre.y() + 2e-7, lo.z() - 1.0);
        const Eigen::Vector3d direction(1e-9, 2e-9, 1.0);
        std::vector<double> hits = query.ray_hits(origin, direction);
        for (int k = 0; k < image.dims.z(); ++k) {
          const double z = image.origin_mm.z() + k * spacing_mm.z();
          bool inside = false;
          if (hits.size() % 2 == 0) {
            int crossed = 0;
            for (double t : hits)
              crossed += origin.z() + t * direction.z() < z ? 1 : 0;
            inside = crossed % 2 == 1;
          } else {
            inside = query.inside(image.physical_point(Eigen::Vector3d(i, j, k)));
          }
          if (inside)
            image(i, j, k) = part.label;
        }
      }
    progress.advance();
  }
  progress.finish();
  return image;
}

} // namespace ligsim::labelmap
