#include "sim/membrane/scene/tear_metrics.hpp"

#include <cmath>
#include <limits>
#include <numeric>

namespace ligsim::membrane {

double mean_tear_direction_deg(const std::vector<TearEvent>& events)
{
  Vec2 doubled = Vec2::Zero();
  for (const TearEvent& event : events) {
    const Vec2 segment = event.to_rest - event.from_rest;
    const double angle = std::atan2(segment.y(), segment.x());
    doubled += segment.norm() * Vec2(std::cos(2.0 * angle), std::sin(2.0 * angle));
  }
  if (!(doubled.norm() > 0.0))
    return std::numeric_limits<double>::quiet_NaN();
  double degrees = 0.5 * std::atan2(doubled.y(), doubled.x()) * 180.0 / M_PI;
  if (degrees < 0.0)
    degrees += 180.0;
  return degrees >= 180.0 ? 0.0 : degrees;
}

RadiusStatistics tear_radius(const std::vector<TearEvent>& events, const Vec2& centre)
{
  RadiusStatistics stats;
  std::vector<double> radii;
  for (const TearEvent& event : events)
    radii.push_back((event.to_rest - centre).norm());
  stats.points = static_cast<int>(radii.size());
  if (radii.empty())
    return stats;
  stats.mean_mm = std::accumulate(radii.begin(), radii.end(), 0.0) / radii.size();
  double sum = 0.0;
  for (double r : radii)
    sum += (r - stats.mean_mm) * (r - stats.mean_mm);
  stats.standard_deviation_mm = std::sqrt(sum / radii.size());
  stats.coefficient_of_variation =
      stats.mean_mm > 0.0 ? stats.standard_deviation_mm / stats.mean_mm : 0.0;
  return stats;
}

int component_count(const MembraneMesh& mesh)
{
  std::vector<int> parent(mesh.node_count());
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int i) {
    while (parent[i] != i)
      i = parent[i] = parent[parent[i]];
    return i;
  };
  for (const Triangle& t : mesh.triangles) {
    parent[root(t[1])] = root(t[0]);
    parent[root(t[2])] = root(t[0]);
  }
  int count = 0;
  for (int v = 0; v < mesh.node_count(); ++v)
    count += root(v) == v;
  return count;
}

} // namespace ligsim::membrane
