#include "stages/distance/distance.hpp"

#include "common/progress.hpp"
#include "stages/geometry/surface_query.hpp"

namespace ligsim::distance {

namespace {

/// True for an outside voxel with an inside voxel among its 26 neighbours.
bool touches_inside(const Mask& mask, int i, int j, int k)
{
  for (const Eigen::Vector3i& o : neighbourhood_26()) {
    const int a = i + o.x(), b = j + o.y(), c = k + o.z();
    if (mask.contains(a, b, c) && mask(a, b, c))
      return true;
  }
  return false;
}

} // namespace

ScalarGrid signed_distance(const SurfaceQuery& query, const Mask& mask)
{
  const float far = static_cast<float>(-kFarOutsideVoxels * mask.spacing);
  ScalarGrid distance = ScalarGrid::like(mask, far);
  const auto slices = mask.dims.z();
  Progress progress("distance", static_cast<std::size_t>(slices));
  for (int k = 0; k < slices; ++k) {
#pragma omp parallel for schedule(dynamic, 4)
    for (int j = 0; j < mask.dims.y(); ++j)
      for (int i = 0; i < mask.dims.x(); ++i) {
        const bool inside = mask(i, j, k) != 0;
        if (!inside && !touches_inside(mask, i, j, k))
          continue;
        const double d = query.distance(mask.point(i, j, k));
        distance(i, j, k) = static_cast<float>(inside ? d : -d);
      }
    progress.advance();
  }
  progress.finish();
  return distance;
}

} // namespace ligsim::distance
