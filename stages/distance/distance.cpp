#include "stages/distance/distance.hpp"

#include "common/progress.hpp"
#include "stages/geometry/surface_query.hpp"

namespace ligsim::distance {

ScalarGrid signed_distance(const SurfaceQuery& query, const Mask& mask)
{
  ScalarGrid distance = ScalarGrid::like(mask, 0.0f);
  const auto slices = mask.dims.z();
  Progress progress("distance", static_cast<std::size_t>(slices));
  for (int k = 0; k < slices; ++k) {
#pragma omp parallel for schedule(dynamic, 4)
    for (int j = 0; j < mask.dims.y(); ++j)
      for (int i = 0; i < mask.dims.x(); ++i) {
        const double d = query.distance(mask.point(i, j, k));
        distance(i, j, k) = static_cast<float>(mask(i, j, k) ? d : -d);
      }
    progress.advance();
  }
  progress.finish();
  return distance;
}

} // namespace ligsim::distance
