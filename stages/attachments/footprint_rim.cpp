#include "stages/attachments/footprint_rim.hpp"

#include "common/error.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <map>
#include <utility>

namespace ligsim::attachments {
namespace {

using Edge = std::pair<int, int>; // sorted vertex indices

Edge edge_of(int a, int b)
{
  return a < b ? Edge{a, b} : Edge{b, a};
}

} // namespace

std::vector<FeatureLine> footprint_rims(const TriangleSurface& surface,
                                        const std::vector<int>& area)
{
  std::vector<bool> in_area(static_cast<std::size_t>(surface.V.rows()), false);
  for (int v : area)
    in_area.at(static_cast<std::size_t>(v)) = true;

  // Each mixed edge (one corner in the area) carries one point of the level set; each triangle
  // with mixed edges joins its two. On a closed manifold every mixed edge has two triangles, so
  // every point has two neighbours and the segments chain into loops.
  std::map<Edge, std::vector<Edge>> neighbours;
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f) {
    std::vector<Edge> mixed;
    for (int k = 0; k < 3; ++k) {
      const int a = surface.F(f, k), b = surface.F(f, (k + 1) % 3);
      if (in_area[static_cast<std::size_t>(a)] != in_area[static_cast<std::size_t>(b)])
        mixed.push_back(edge_of(a, b));
    }
    if (mixed.empty())
      continue;
    neighbours[mixed[0]].push_back(mixed[1]);
    neighbours[mixed[1]].push_back(mixed[0]);
  }
  for (const auto& [edge, next] : neighbours)
    if (next.size() != 2)
      fail("footprint rim: the edge ({}, {}) leaving the attachment area has {} triangles, not "
           "2: the surface is not closed and manifold there",
           edge.first, edge.second, next.size());

  const auto midpoint = [&](const Edge& e) -> Eigen::Vector3d {
    return 0.5 * (surface.V.row(e.first) + surface.V.row(e.second)).transpose();
  };
  std::vector<FeatureLine> rims;
  std::map<Edge, bool> visited;
  for (const auto& [start, ignored] : neighbours) {
    if (visited[start])
      continue;
    FeatureLine rim{midpoint(start)};
    Edge previous = start, current = neighbours.at(start)[0];
    visited[start] = true;
    while (current != start) {
      visited[current] = true;
      rim.push_back(midpoint(current));
      const std::vector<Edge>& next = neighbours.at(current);
      const Edge following = next[0] == previous ? next[1] : next[0];
      previous = std::exchange(current, following);
    }
    rim.push_back(rim.front());
    rims.push_back(std::move(rim));
  }
  return rims;
}

double footprint_share(const TriangleSurface& surface, const std::vector<bool>& in_area, int face,
                       const Eigen::Vector3d& point)
{
  const Eigen::Vector3d a = surface.V.row(surface.F(face, 0)).transpose();
  const Eigen::Vector3d b = surface.V.row(surface.F(face, 1)).transpose();
  const Eigen::Vector3d c = surface.V.row(surface.F(face, 2)).transpose();
  Eigen::Matrix<double, 3, 2> edges;
  edges << b - a, c - a;
  // Least squares: the point lies on the triangle's plane up to round-off.
  const Eigen::Vector2d uv = edges.colPivHouseholderQr().solve(point - a);
  const Eigen::Vector3d weights(1.0 - uv.sum(), uv.x(), uv.y());
  double share = 0.0;
  for (int k = 0; k < 3; ++k)
    if (in_area[static_cast<std::size_t>(surface.F(face, k))])
      share += std::clamp(weights(k), 0.0, 1.0);
  return share;
}

double feature_length(const FeatureLine& line)
{
  double length = 0.0;
  for (std::size_t i = 1; i < line.size(); ++i)
    length += (line[i] - line[i - 1]).norm();
  return length;
}

} // namespace ligsim::attachments
