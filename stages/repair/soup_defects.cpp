#include "stages/repair/soup_defects.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <map>
#include <numeric>
#include <set>
#include <utility>

namespace ligsim::repair {

namespace {

constexpr std::size_t kReportedLocations = 5;

Eigen::Vector3d point(const Points& V, int v)
{
  return V.row(v).transpose();
}

Location triangle_location(const Points& V, const std::array<int, 3>& t)
{
  return {(point(V, t[0]) + point(V, t[1]) + point(V, t[2])) / 3.0, {t[0], t[1], t[2]}, {}};
}

Location edge_location(const Points& V, int a, int b)
{
  return {0.5 * (point(V, a) + point(V, b)), {a, b}, {point(V, a), point(V, b)}};
}

using Edge = std::pair<int, int>;
Edge undirected(int a, int b)
{
  return {std::min(a, b), std::max(a, b)};
}

/// Triangles around each undirected edge.
std::map<Edge, std::vector<int>> edge_triangles(const Soup& triangles)
{
  std::map<Edge, std::vector<int>> edges;
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int e = 0; e < 3; ++e)
      edges[undirected(triangles[t][e], triangles[t][(e + 1) % 3])].push_back(static_cast<int>(t));
  return edges;
}

int find_root(std::vector<int>& parent, int i)
{
  while (parent[i] != i)
    i = parent[i] = parent[parent[i]];
  return i;
}

} // namespace

void add_location(Repair& repair, const Location& location)
{
  if (repair.locations.size() < kReportedLocations)
    repair.locations.push_back(location);
}

Repair merge_duplicate_vertices(const Points& V, Soup& triangles)
{
  Repair repair{"duplicate_vertices", "merged", 0, {}};
  std::vector<bool> used(static_cast<std::size_t>(V.rows()), false);
  for (const auto& t : triangles)
    for (int v : t)
      used[static_cast<std::size_t>(v)] = true;
  std::map<std::array<double, 3>, int> first;
  std::vector<int> target(used.size(), -1);
  for (int v = 0; v < static_cast<int>(used.size()); ++v) {
    if (!used[static_cast<std::size_t>(v)])
      continue;
    const auto [it, inserted] = first.emplace(std::array{V(v, 0), V(v, 1), V(v, 2)}, v);
    target[static_cast<std::size_t>(v)] = it->second;
    if (!inserted) {
      ++repair.count;
      add_location(repair, {point(V, v), {it->second, v}, {point(V, v), point(V, v)}});
    }
  }
  for (auto& t : triangles)
    for (int& v : t)
      v = target[static_cast<std::size_t>(v)];
  return repair;
}

Repair remove_degenerate(const Points& V, Soup& triangles)
{
  Repair repair{"degenerate_triangles", "removed", 0, {}};
  Soup kept;
  kept.reserve(triangles.size());
  for (const auto& t : triangles) {
    const Eigen::Vector3d a = point(V, t[0]), b = point(V, t[1]), c = point(V, t[2]);
    const bool repeated = t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
    if (repeated || (b - a).cross(c - a).norm() == 0.0) {
      ++repair.count;
      add_location(repair, triangle_location(V, t));
    } else {
      kept.push_back(t);
    }
  }
  triangles.swap(kept);
  return repair;
}

Repair remove_duplicates(const Points& V, Soup& triangles)
{
  Repair repair{"duplicate_triangles", "removed", 0, {}};
  std::set<std::array<int, 3>> seen;
  Soup kept;
  kept.reserve(triangles.size());
  for (const auto& t : triangles) {
    std::array<int, 3> key = t;
    std::sort(key.begin(), key.end());
    if (seen.insert(key).second) {
      kept.push_back(t);
    } else {
      ++repair.count;
      add_location(repair, triangle_location(V, t));
    }
  }
  triangles.swap(kept);
  return repair;
}

Repair find_nonmanifold_edges(const Points& V, const Soup& triangles)
{
  Repair repair{"non_manifold_edges", "split", 0, {}};
  for (const auto& [edge, around] : edge_triangles(triangles))
    if (around.size() > 2) {
      ++repair.count;
      add_location(repair, edge_location(V, edge.first, edge.second));
    }
  return repair;
}

Repair find_inconsistent_edges(const Points& V, const Soup& triangles)
{
  Repair repair{"inconsistent_orientation", "flipped", 0, {}};
  std::map<Edge, std::pair<int, int>> runs; // (count a->b, count b->a) with a < b
  for (const auto& t : triangles)
    for (int e = 0; e < 3; ++e) {
      const int u = t[e], v = t[(e + 1) % 3];
      auto& count = runs[undirected(u, v)];
      (u < v ? count.first : count.second) += 1;
    }
  for (const auto& [edge, count] : runs)
    if (count.first + count.second == 2 && count.first != 1) {
      ++repair.count;
      add_location(repair, edge_location(V, edge.first, edge.second));
    }
  return repair;
}

Repair find_nonmanifold_vertices(const Points& V, const Soup& triangles)
{
  Repair repair{"non_manifold_vertices", "split", 0, {}};
  const auto edges = edge_triangles(triangles);
  std::vector<std::vector<int>> around(static_cast<std::size_t>(V.rows()));
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int v : triangles[t])
      around[static_cast<std::size_t>(v)].push_back(static_cast<int>(t));
  std::vector<bool> on_nonmanifold_edge(around.size(), false);
  for (const auto& [edge, list] : edges)
    if (list.size() > 2)
      on_nonmanifold_edge[edge.first] = on_nonmanifold_edge[edge.second] = true;

  for (int v = 0; v < static_cast<int>(around.size()); ++v) {
    const std::vector<int>& fan = around[static_cast<std::size_t>(v)];
    if (fan.size() < 2 || on_nonmanifold_edge[static_cast<std::size_t>(v)])
      continue;
    // Triangles at v joined through the edges at v: one group for a manifold vertex.
    std::vector<int> parent(fan.size());
    std::iota(parent.begin(), parent.end(), 0);
    for (std::size_t i = 0; i < fan.size(); ++i)
      for (int w : triangles[static_cast<std::size_t>(fan[i])]) {
        if (w == v)
          continue;
        for (int t : edges.at(undirected(v, w))) {
          const auto j = std::find(fan.begin(), fan.end(), t) - fan.begin();
          parent[find_root(parent, static_cast<int>(i))] = find_root(parent, static_cast<int>(j));
        }
      }
    int groups = 0;
    for (std::size_t i = 0; i < fan.size(); ++i)
      groups += find_root(parent, static_cast<int>(i)) == static_cast<int>(i) ? 1 : 0;
    if (groups > 1) {
      ++repair.count;
      add_location(repair, {point(V, v), {v}, {point(V, v)}});
    }
  }
  return repair;
}

} // namespace ligsim::repair
