#include "stages/geometry/grid.hpp"

namespace ligsim {

const std::vector<Eigen::Vector3i>& neighbourhood_26()
{
  static const std::vector<Eigen::Vector3i> offsets = [] {
    std::vector<Eigen::Vector3i> result;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          if (dx != 0 || dy != 0 || dz != 0)
            result.emplace_back(dx, dy, dz);
    return result;
  }();
  return offsets;
}

} // namespace ligsim
