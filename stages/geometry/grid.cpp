#include "stages/geometry/grid.hpp"

namespace ligsim {

std::size_t inside_count(const Mask& mask)
{
  std::size_t count = 0;
  mask.for_each_stored(
      [&](const Eigen::Vector3i&, std::uint8_t inside) { count += inside ? 1 : 0; });
  return count;
}

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
