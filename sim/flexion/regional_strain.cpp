#include "sim/flexion/regional_strain.hpp"

#include "common/error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

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
    , m_centroids(centroids)
    , m_volumes(volumes)
{
  if (!(radius_mm > 0.0) || !std::isfinite(radius_mm))
    fail("regional strain: the region radius must be a positive number of mm, not {}", radius_mm);
  if (centroids.rows() != volumes.size())
    fail("regional strain: {} centroids but {} volumes", centroids.rows(), volumes.size());
  for (Eigen::Index e = 0; e < centroids.rows(); ++e)
    m_cells[cell_key(centroids.row(e).transpose(), radius_mm)].push_back(static_cast<int>(e));
}

double RegionalMean::mean(const Eigen::VectorXd& per_element, Eigen::Index e) const
{
  const Eigen::Vector3d c = m_centroids.row(e).transpose();
  const double r2 = m_radius_mm * m_radius_mm;
  double sum = 0.0;
  double volume = 0.0;
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dz = -1; dz <= 1; ++dz) {
        const auto found = m_cells.find(cell_key(c, m_radius_mm, dx, dy, dz));
        if (found == m_cells.end())
          continue;
        for (int other : found->second)
          if ((m_centroids.row(other).transpose() - c).squaredNorm() <= r2) {
            sum += m_volumes[other] * per_element[other];
            volume += m_volumes[other];
          }
      }
  return volume > 0.0 ? sum / volume : per_element[e];
}

double RegionalMean::max_mean(const Eigen::VectorXd& per_element) const
{
  if (per_element.size() != m_volumes.size())
    fail("regional strain: {} values for {} elements", per_element.size(), m_volumes.size());
  if (!m_regions && !m_too_many)
    list_regions();
  double best = -INFINITY;
  if (m_regions) {
    for (Eigen::Index e = 0; e < per_element.size(); ++e) {
      double sum = 0.0;
      for (int k = m_regions->start[e]; k < m_regions->start[e + 1]; ++k) {
        const int other = m_regions->members[k];
        sum += m_volumes[other] * per_element[other];
      }
      best =
          std::max(best, m_regions->volume[e] > 0.0 ? sum / m_regions->volume[e] : per_element[e]);
    }
    return best;
  }
  for_each_region([&](Eigen::Index e, const std::vector<int>& candidates) {
    const Eigen::Vector3d c = m_centroids.row(e).transpose();
    double sum = 0.0, volume = 0.0;
    for (int other : candidates)
      if ((m_centroids.row(other).transpose() - c).squaredNorm() <= m_radius_mm * m_radius_mm) {
        sum += m_volumes[other] * per_element[other];
        volume += m_volumes[other];
      }
    best = std::max(best, volume > 0.0 ? sum / volume : per_element[e]);
    return true;
  });
  return best;
}

template <class Visit> void RegionalMean::for_each_region(Visit&& visit) const
{
  // Cell by cell: the 27 cells around one are looked up once for all its elements, their
  // elements in mean()'s order (the same sums).
  std::vector<int> candidates;
  for (const auto& [key, elements] : m_cells) {
    const Eigen::Vector3d inside = m_centroids.row(elements.front()).transpose();
    candidates.clear();
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz)
          if (const auto found = m_cells.find(cell_key(inside, m_radius_mm, dx, dy, dz));
              found != m_cells.end())
            candidates.insert(candidates.end(), found->second.begin(), found->second.end());
    for (int e : elements)
      if (!visit(static_cast<Eigen::Index>(e), candidates))
        return;
  }
}

void RegionalMean::list_regions() const
{
  constexpr std::size_t kMaxListed = 4'000'000; // 16 MB of indices
  const Eigen::Index n = m_volumes.size();
  std::vector<std::vector<int>> lists(static_cast<std::size_t>(n));
  std::size_t listed = 0;
  const double r2 = m_radius_mm * m_radius_mm;
  for_each_region([&](Eigen::Index e, const std::vector<int>& candidates) {
    const Eigen::Vector3d c = m_centroids.row(e).transpose();
    std::vector<int>& list = lists[static_cast<std::size_t>(e)];
    for (int other : candidates)
      if ((m_centroids.row(other).transpose() - c).squaredNorm() <= r2)
        list.push_back(other);
    listed += list.size();
    return listed <= kMaxListed;
  });
  if (listed > kMaxListed) {
    m_too_many = true;
    return;
  }
  Regions regions;
  regions.start.reserve(static_cast<std::size_t>(n) + 1);
  regions.members.reserve(listed);
  regions.volume = Eigen::VectorXd::Zero(n);
  for (Eigen::Index e = 0; e < n; ++e) {
    regions.start.push_back(static_cast<int>(regions.members.size()));
    for (int other : lists[static_cast<std::size_t>(e)]) {
      regions.members.push_back(other);
      regions.volume[e] += m_volumes[other];
    }
  }
  regions.start.push_back(static_cast<int>(regions.members.size()));
  m_regions = std::move(regions);
}

} // namespace ligsim::sim
