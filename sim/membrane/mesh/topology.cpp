#include "sim/membrane/mesh/topology.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <utility>

namespace ligsim::membrane {
namespace {

int next(int k)
{
  return (k + 1) % 3;
}
int prev(int k)
{
  return (k + 2) % 3;
}

/// Splits the triangle whose side `s` = (b, c) gets the new node p; the triangle becomes
/// (a, b, p) in place and (a, p, c) is appended.
void split_triangle_at_side(MembraneMesh& mesh, int tri, int s, int p, TopologyEdit& edit)
{
  const Triangle t = mesh.triangles[tri];
  const auto cut = mesh.side_cut[tri];
  const auto load = mesh.side_load[tri];
  const int b = t[s], c = t[next(s)], a = t[prev(s)];
  mesh.triangles[tri] = {a, b, p};
  mesh.side_cut[tri] = {cut[prev(s)], cut[s], false};
  mesh.side_load[tri] = {load[prev(s)], load[s], 0};
  const int child = mesh.add_triangle({a, p, c}, mesh.fiber_angle_rad[tri],
                                      {false, cut[s], cut[next(s)]}, {0, load[s], load[next(s)]});
  edit.touch(tri, tri);
  edit.touch(child, tri);
}

/// Appends the rest corners of the two triangles split_triangle_at_side would make.
void children_at_side(const MembraneMesh& mesh, int tri, int s, const Vec2& p,
                      std::vector<std::array<Vec2, 3>>& out)
{
  const Triangle& t = mesh.triangles[tri];
  const Vec2& a = mesh.rest[t[prev(s)]];
  const Vec2& b = mesh.rest[t[s]];
  const Vec2& c = mesh.rest[t[next(s)]];
  out.push_back({a, b, p});
  out.push_back({a, p, c});
}

SplitQuality quality_of(const std::vector<std::array<Vec2, 3>>& triangles)
{
  SplitQuality quality{M_PI, std::numeric_limits<double>::infinity()};
  for (const auto& t : triangles) {
    quality.min_angle_rad = std::min(quality.min_angle_rad, min_angle(t[0], t[1], t[2]));
    quality.min_area_mm2 = std::min(quality.min_area_mm2, signed_area(t[0], t[1], t[2]));
  }
  return quality;
}

/// Union-find root with path halving.
int root(std::vector<int>& parent, int i)
{
  while (parent[i] != i)
    i = parent[i] = parent[parent[i]];
  return i;
}

} // namespace

std::optional<SideRef> opposite_side(const MembraneMesh& mesh, const NodeIncidence& incidence,
                                     SideRef side)
{
  const Triangle& t = mesh.triangles[side.triangle];
  const int b = t[side.side], c = t[next(side.side)];
  for (const int* other = incidence.begin(b); other != incidence.end(b); ++other) {
    if (*other == side.triangle)
      continue;
    const Triangle& u = mesh.triangles[*other];
    const int k = local_index(u, c);
    if (k >= 0 && u[next(k)] == b)
      return SideRef{*other, k};
  }
  return std::nullopt;
}

bool is_enclosed(const MembraneMesh& mesh, const NodeIncidence& incidence, int node)
{
  double total = 0.0;
  for (const int* tri = incidence.begin(node); tri != incidence.end(node); ++tri) {
    const Triangle& t = mesh.triangles[*tri];
    const int k = local_index(t, node);
    const Vec2 u = mesh.rest[t[next(k)]] - mesh.rest[node];
    const Vec2 w = mesh.rest[t[prev(k)]] - mesh.rest[node];
    total += std::atan2(cross(u, w), u.dot(w));
  }
  return std::abs(total - 2.0 * M_PI) < 1e-6;
}

bool is_cuttable_edge(const MembraneMesh& mesh, const NodeIncidence& incidence, int a, int b)
{
  for (const int* tri = incidence.begin(a); tri != incidence.end(a); ++tri) {
    const Triangle& t = mesh.triangles[*tri];
    const int k = local_index(t, a);
    if (t[next(k)] != b)
      continue;
    return !mesh.side_cut[*tri][k] && opposite_side(mesh, incidence, {*tri, k}).has_value();
  }
  return false;
}

SplitQuality side_split_quality(const MembraneMesh& mesh, const NodeIncidence& incidence,
                                SideRef side, double t)
{
  const Triangle& tri = mesh.triangles[side.triangle];
  const Vec2 p = (1.0 - t) * mesh.rest[tri[side.side]] + t * mesh.rest[tri[next(side.side)]];
  std::vector<std::array<Vec2, 3>> children;
  children_at_side(mesh, side.triangle, side.side, p, children);
  if (const auto other = opposite_side(mesh, incidence, side))
    children_at_side(mesh, other->triangle, other->side, p, children);
  return quality_of(children);
}

int split_side(MembraneMesh& mesh, const NodeIncidence& incidence, SideRef side, double t,
               TopologyEdit& edit)
{
  const Triangle tri = mesh.triangles[side.triangle];
  const auto other = opposite_side(mesh, incidence, side);
  const int p = mesh.add_node_between(tri[side.side], tri[next(side.side)], t);
  edit.new_nodes.push_back(p);
  split_triangle_at_side(mesh, side.triangle, side.side, p, edit);
  if (other)
    split_triangle_at_side(mesh, other->triangle, other->side, p, edit);
  return p;
}

SplitQuality centroid_quality(const MembraneMesh& mesh, int tri)
{
  const Triangle& t = mesh.triangles[tri];
  const Vec2 centre = (mesh.rest[t[0]] + mesh.rest[t[1]] + mesh.rest[t[2]]) / 3.0;
  std::vector<std::array<Vec2, 3>> children;
  for (int k = 0; k < 3; ++k)
    children.push_back({mesh.rest[t[k]], mesh.rest[t[next(k)]], centre});
  return quality_of(children);
}

int insert_centroid(MembraneMesh& mesh, int tri, TopologyEdit& edit)
{
  const Triangle t = mesh.triangles[tri];
  const auto cut = mesh.side_cut[tri];
  const auto load = mesh.side_load[tri];
  const int centre = mesh.add_node_at_centroid(tri);
  edit.new_nodes.push_back(centre);
  mesh.triangles[tri] = {t[0], t[1], centre};
  mesh.side_cut[tri] = {cut[0], false, false};
  mesh.side_load[tri] = {load[0], 0, 0};
  edit.touch(tri, tri);
  for (int k = 1; k < 3; ++k)
    edit.touch(mesh.add_triangle({t[k], t[next(k)], centre}, mesh.fiber_angle_rad[tri],
                                 {cut[k], false, false}, {load[k], 0, 0}),
               tri);
  return centre;
}

void cut_edge(MembraneMesh& mesh, const NodeIncidence& incidence, int a, int b)
{
  for (const int* tri = incidence.begin(a); tri != incidence.end(a); ++tri) {
    const Triangle& t = mesh.triangles[*tri];
    const int k = local_index(t, a);
    if (t[next(k)] == b) {
      mesh.side_cut[*tri][k] = true;
      if (const auto other = opposite_side(mesh, incidence, {*tri, k}))
        mesh.side_cut[other->triangle][other->side] = true;
      return;
    }
  }
}

std::vector<int> split_fans(MembraneMesh& mesh, const NodeIncidence& incidence, int node,
                            TopologyEdit& edit)
{
  const std::vector<int> around(incidence.begin(node), incidence.end(node));
  const int n = static_cast<int>(around.size());
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  for (int i = 0; i < n; ++i) {
    const Triangle& t = mesh.triangles[around[i]];
    const int k = local_index(t, node);
    // Side k leaves the node towards t[k+1]; its neighbour enters the node from there.
    const auto other = opposite_side(mesh, incidence, {around[i], k});
    if (!other || mesh.side_cut[around[i]][k] || mesh.side_cut[other->triangle][other->side])
      continue;
    const int j =
        static_cast<int>(std::find(around.begin(), around.end(), other->triangle) - around.begin());
    parent[root(parent, i)] = root(parent, j);
  }
  std::map<int, int> copy_of_fan; // fan root -> node used by that fan
  copy_of_fan[root(parent, 0)] = node;
  std::vector<int> copies;
  for (int i = 0; i < n; ++i) {
    const int fan = root(parent, i);
    auto found = copy_of_fan.find(fan);
    if (found == copy_of_fan.end()) {
      const int copy = mesh.add_node_copy(node);
      if (copies.empty())
        edit.split_nodes.push_back(node);
      copies.push_back(copy);
      edit.new_nodes.push_back(copy);
      found = copy_of_fan.emplace(fan, copy).first;
    }
    if (found->second != node) {
      Triangle& t = mesh.triangles[around[i]];
      t[local_index(t, node)] = found->second;
      edit.touch(around[i], around[i]);
    }
  }
  return copies;
}

std::string manifold_problem(const MembraneMesh& mesh)
{
  for (int tri = 0; tri < mesh.triangle_count(); ++tri) {
    const Triangle& t = mesh.triangles[tri];
    for (int v : t)
      if (v < 0 || v >= mesh.node_count())
        return fmt::format("triangle {} refers to node {} of {}", tri, v, mesh.node_count());
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
      return fmt::format("triangle {} repeats a node", tri);
    if (!(rest_area(mesh, tri) > 0.0))
      return fmt::format("triangle {} has rest area {} <= 0", tri, rest_area(mesh, tri));
  }
  // Directed edges: each at most once; a shared edge appears once in each direction.
  std::map<std::pair<int, int>, SideRef> directed;
  for (int tri = 0; tri < mesh.triangle_count(); ++tri)
    for (int k = 0; k < 3; ++k) {
      const Triangle& t = mesh.triangles[tri];
      if (!directed.emplace(std::pair{t[k], t[next(k)]}, SideRef{tri, k}).second)
        return fmt::format("edge ({}, {}) appears twice with the same orientation", t[k],
                           t[next(k)]);
    }
  for (const auto& [edge, side] : directed) {
    const auto reverse = directed.find({edge.second, edge.first});
    if (reverse != directed.end() &&
        mesh.side_cut[side.triangle][side.side] !=
            mesh.side_cut[reverse->second.triangle][reverse->second.side])
      return fmt::format("edge ({}, {}) is cut on one side only", edge.first, edge.second);
  }
  // Every node: one fan, linked through shared edges; 0 or 2 boundary edges.
  const NodeIncidence incidence = build_incidence(mesh);
  for (int v = 0; v < mesh.node_count(); ++v) {
    const std::vector<int> around(incidence.begin(v), incidence.end(v));
    if (around.empty())
      return fmt::format("node {} belongs to no triangle", v);
    std::vector<int> parent(around.size());
    std::iota(parent.begin(), parent.end(), 0);
    int boundary_edges = 0;
    for (std::size_t i = 0; i < around.size(); ++i) {
      const Triangle& t = mesh.triangles[around[i]];
      const int k = local_index(t, v);
      for (int s : {k, prev(k)}) {
        const auto other = opposite_side(mesh, incidence, {around[i], s});
        if (!other) {
          ++boundary_edges;
          continue;
        }
        const auto j = std::find(around.begin(), around.end(), other->triangle) - around.begin();
        parent[root(parent, static_cast<int>(i))] = root(parent, static_cast<int>(j));
      }
    }
    for (std::size_t i = 1; i < around.size(); ++i)
      if (root(parent, static_cast<int>(i)) != root(parent, 0))
        return fmt::format("node {} joins {} triangles that form more than one fan", v,
                           around.size());
    if (boundary_edges != 0 && boundary_edges != 2)
      return fmt::format("node {} has {} boundary edges (a manifold node has 0 or 2)", v,
                         boundary_edges);
  }
  return {};
}

} // namespace ligsim::membrane
