#include "stages/distance/distance.hpp"

#include "common/progress.hpp"
#include "stages/geometry/surface_query.hpp"
#include "stages/voxelize/level_set.hpp"

#include <algorithm>

namespace ligsim::distance {

ScalarGrid signed_distance(const vdb::LevelSet& level_set, const SurfaceQuery& query)
{
  const double spacing = level_set.spacing_mm();
  const double band = level_set.exterior_band_voxels() * spacing;
  const auto far = static_cast<float>(kFarOutsideVoxels * spacing);
  // OpenVDB's values, positive inside, -band beyond its exterior band.
  const ScalarGrid estimate = level_set.signed_distance(band);
  ScalarGrid exact = ScalarGrid::with_bricks_of(estimate, -far);
  const auto bricks = static_cast<std::ptrdiff_t>(estimate.brick_count());
  Progress progress("distance", static_cast<std::size_t>(bricks));
#pragma omp parallel for schedule(dynamic, 16)
  for (std::ptrdiff_t b = 0; b < bricks; ++b) {
    estimate.for_each_in_brick(
        static_cast<std::size_t>(b), [&](const Eigen::Vector3i& v, float value) {
          if (value <= static_cast<float>(-band))
            return; // beyond the exterior band: farther than `far`
          const auto d = static_cast<float>(query.distance(estimate.point_of(v)));
          *exact.find(v.x(), v.y(), v.z()) = value > 0.0f ? d : -std::min(d, far);
        });
#pragma omp critical(distance_progress)
    progress.advance();
  }
  progress.finish();
  return exact.pruned(); // the bricks of the band's outer layer may hold only -far
}

} // namespace ligsim::distance
