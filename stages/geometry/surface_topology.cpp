#include "stages/geometry/surface_topology.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <map>
#include <utility>

namespace ligsim {

namespace {
constexpr std::size_t kReportedLocations = 5;
}

TopologyReport check_topology(const TriangleSurface& surface)
{
  TopologyReport report;
  // Directed-edge counts per undirected edge: (count a->b, count b->a) with a < b.
  std::map<std::pair<int, int>, std::pair<int, int>> edges;
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f) {
    const Eigen::Vector3i t = surface.F.row(f);
    const Eigen::Vector3d a = surface.V.row(t[0]), b = surface.V.row(t[1]), c = surface.V.row(t[2]);
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || (b - a).cross(c - a).norm() == 0.0)
      ++report.degenerate_triangles;
    for (int e = 0; e < 3; ++e) {
      const int u = t[e], v = t[(e + 1) % 3];
      auto& count = edges[{std::min(u, v), std::max(u, v)}];
      (u < v ? count.first : count.second) += 1;
    }
  }
  bool first_boundary = true;
  for (const auto& [edge, count] : edges) {
    const int total = count.first + count.second;
    if (total == 1) {
      ++report.boundary_edges;
      const Eigen::Vector3d p = surface.V.row(edge.first), q = surface.V.row(edge.second);
      if (report.boundary_edge_midpoints.size() < kReportedLocations)
        report.boundary_edge_midpoints.push_back(0.5 * (p + q));
      const Eigen::Vector3d lo = p.cwiseMin(q), hi = p.cwiseMax(q);
      report.boundary_min = first_boundary ? lo : report.boundary_min.cwiseMin(lo);
      report.boundary_max = first_boundary ? hi : report.boundary_max.cwiseMax(hi);
      first_boundary = false;
    } else if (total > 2) {
      ++report.nonmanifold_edges;
      if (report.nonmanifold_edge_list.size() < kReportedLocations)
        report.nonmanifold_edge_list.push_back(edge);
    } else if (count.first != 1) {
      ++report.inconsistent_edges;
      if (report.inconsistent_edge_list.size() < kReportedLocations)
        report.inconsistent_edge_list.push_back(edge);
    }
  }
  return report;
}

double signed_volume(const TriangleSurface& surface)
{
  double six_volume = 0.0;
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f) {
    const Eigen::Vector3d a = surface.V.row(surface.F(f, 0));
    const Eigen::Vector3d b = surface.V.row(surface.F(f, 1));
    const Eigen::Vector3d c = surface.V.row(surface.F(f, 2));
    six_volume += a.dot(b.cross(c));
  }
  return six_volume / 6.0;
}

double surface_area(const TriangleSurface& surface)
{
  double twice_area = 0.0;
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f) {
    const Eigen::Vector3d a = surface.V.row(surface.F(f, 0));
    const Eigen::Vector3d b = surface.V.row(surface.F(f, 1));
    const Eigen::Vector3d c = surface.V.row(surface.F(f, 2));
    twice_area += (b - a).cross(c - a).norm();
  }
  return 0.5 * twice_area;
}

} // namespace ligsim
