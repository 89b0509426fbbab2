#include "sim/flexion/regional_strain.hpp"

#include "common/error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace ligsim::sim {

namespace {

/// Key of the grid cell of edge `cell` that holds point p.
std::int64_t cell_key(const Eigen::Vector3d& p, double cell, int dx = 0, int dy = 0, int dz = 0)
{
  const auto index = [&](double v, int d) {
    return static_cast<std::int64_t>(std::floor(v / cell)) + d + (std::int64_t(1) << 20);
  };
  return (index(p.x(), dx) << 42) | (index(p.y(), dy) << 21) | index(p.z(), dz);
}

} // namespace

RegionalMean::RegionalMean(const Eigen::MatrixX3d& centroids, const Eigen::VectorXd& volumes,
                           double radius_mm)
    : m_radius_mm(radius_mm)
    , m_volumes(volumes)
{
  if (!(radius_mm > 0.0) || !std::isfinite(radius_mm))
    fail("regional strain: the region radius must be a positive number of mm, not {}", radius_mm);
  if (centroids.rows() != volumes.size())
    fail("regional strain: {} centroids but {} volumes", centroids.rows(), volumes.size());
  // Points are binned in cells of the radius, so a region lies within the 27 cells around it.
  std::unordered_map<std::int64_t, std::vector<int>> cells;
  for (Eigen::Index e = 0; e < centroids.rows(); ++e)
    cells[cell_key(centroids.row(e).transpose(), radius_mm)].push_back(static_cast<int>(e));
  const double r2 = radius_mm * radius_mm;
  m_regions.resize(static_cast<std::size_t>(centroids.rows()));
  for (Eigen::Index e = 0; e < centroids.rows(); ++e) {
    const Eigen::Vector3d c = centroids.row(e).transpose();
    std::vector<int>& region = m_regions[static_cast<std::size_t>(e)];
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto found = cells.find(cell_key(c, radius_mm, dx, dy, dz));
          if (found == cells.end())
            continue;
          for (int other : found->second)
            if ((centroids.row(other).transpose() - c).squaredNorm() <= r2)
              region.push_back(other);
        }
  }
}

double RegionalMean::mean(const Eigen::VectorXd& per_element, Eigen::Index e) const
{
  double sum = 0.0;
  double volume = 0.0;
  for (int other : m_regions[static_cast<std::size_t>(e)]) {
    sum += m_volumes[other] * per_element[other];
    volume += m_volumes[other];
  }
  return volume > 0.0 ? sum / volume : per_element[e];
}

double RegionalMean::max_mean(const Eigen::VectorXd& per_element) const
{
  if (per_element.size() != m_volumes.size())
    fail("regional strain: {} values for {} elements", per_element.size(), m_volumes.size());
  double best = -INFINITY;
  for (Eigen::Index e = 0; e < per_element.size(); ++e)
    best = std::max(best, mean(per_element, e));
  return best;
}

} // namespace ligsim::sim
