#include "sim/membrane/crack/propagation.hpp"

#include "common/error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ligsim::membrane {
namespace {

/// The uncut interior edge from `tip` closest in angle to d, within 90 degrees; -1 if none.
int closest_edge(const MembraneMesh& mesh, const NodeIncidence& incidence, int tip, const Vec2& d)
{
  int best = -1;
  double best_cos = 0.0;
  for (const int* tri = incidence.begin(tip); tri != incidence.end(tip); ++tri) {
    const Triangle& t = mesh.triangles[*tri];
    const int w = t[(local_index(t, tip) + 1) % 3];
    const Vec2 along = (mesh.rest[w] - mesh.rest[tip]).normalized();
    if (along.dot(d) > best_cos && is_cuttable_edge(mesh, incidence, tip, w)) {
      best_cos = along.dot(d);
      best = w;
    }
  }
  return best;
}

/// The triangle at `tip` whose corner contains the direction d, as the side opposite the tip.
std::optional<SideRef> side_ahead(const MembraneMesh& mesh, const NodeIncidence& incidence, int tip,
                                  const Vec2& d)
{
  for (const int* tri = incidence.begin(tip); tri != incidence.end(tip); ++tri) {
    const Triangle& t = mesh.triangles[*tri];
    const int k = local_index(t, tip);
    const Vec2 to_b = mesh.rest[t[(k + 1) % 3]] - mesh.rest[tip];
    const Vec2 to_c = mesh.rest[t[(k + 2) % 3]] - mesh.rest[tip];
    if (cross(to_b, d) >= 0.0 && cross(d, to_c) >= 0.0)
      return SideRef{*tri, (k + 1) % 3};
  }
  return std::nullopt;
}

double mean_edge_length(const MembraneMesh& mesh)
{
  double sum = 0.0;
  for (const Triangle& t : mesh.triangles)
    for (int k = 0; k < 3; ++k)
      sum += (mesh.rest[t[(k + 1) % 3]] - mesh.rest[t[k]]).norm();
  return sum / (3.0 * std::max(1, mesh.triangle_count()));
}

void append(TopologyEdit& into, const TopologyEdit& from)
{
  into.triangles.insert(into.triangles.end(), from.triangles.begin(), from.triangles.end());
  into.parents.insert(into.parents.end(), from.parents.begin(), from.parents.end());
  into.new_nodes.insert(into.new_nodes.end(), from.new_nodes.begin(), from.new_nodes.end());
  into.split_nodes.insert(into.split_nodes.end(), from.split_nodes.begin(), from.split_nodes.end());
}

} // namespace

std::optional<CrackAdvance> advance_crack(MembraneMesh& mesh, int tip, const Vec2& d,
                                          const PropagationSettings& settings)
{
  NodeIncidence incidence = build_incidence(mesh);
  const auto ahead = side_ahead(mesh, incidence, tip, d);
  if (!ahead)
    return std::nullopt;
  CrackAdvance advance;
  advance.from = tip;
  advance.from_rest = mesh.rest[tip];

  if (settings.split_faces) {
    // Where the ray tip + s d meets the side (b, c) ahead: b + t (c - b).
    const Triangle& t = mesh.triangles[ahead->triangle];
    const Vec2& b = mesh.rest[t[ahead->side]];
    const Vec2& c = mesh.rest[t[(ahead->side + 1) % 3]];
    const double denominator = cross(c - b, d);
    if (std::abs(denominator) > 0.0) {
      const double along = std::clamp(cross(mesh.rest[tip] - b, d) / denominator, 0.0, 1.0);
      const SplitQuality quality = side_split_quality(mesh, incidence, *ahead, along);
      if (quality.min_angle_rad >= settings.min_angle_rad &&
          quality.min_area_mm2 >= settings.min_area_mm2) {
        advance.to = split_side(mesh, incidence, *ahead, along, advance.edit);
        advance.split_face = true;
        incidence = build_incidence(mesh);
      }
    }
  }
  if (advance.to < 0) { // along an edge: mode 1, or a split snapped to the nearest edge
    advance.to = closest_edge(mesh, incidence, tip, d);
    if (advance.to < 0)
      return std::nullopt;
  }
  cut_edge(mesh, incidence, tip, advance.to);
  advance.to_rest = mesh.rest[advance.to];

  split_fans(mesh, incidence, tip, advance.edit);
  incidence = build_incidence(mesh);
  const bool to_split = !split_fans(mesh, incidence, advance.to, advance.edit).empty();
  incidence = build_incidence(mesh);
  advance.continues = !to_split && is_enclosed(mesh, incidence, advance.to);
  return advance;
}

std::vector<CrackAdvance> initiate_crack(MembraneMesh& mesh, int tri, const Vec2& d,
                                         const PropagationSettings& settings)
{
  TopologyEdit start_edit;
  int start = -1;
  const SplitQuality quality = centroid_quality(mesh, tri);
  if (quality.min_angle_rad >= settings.min_angle_rad &&
      quality.min_area_mm2 >= settings.min_area_mm2) {
    start = insert_centroid(mesh, tri, start_edit);
  } else {
    const NodeIncidence incidence = build_incidence(mesh);
    for (int v : mesh.triangles[tri])
      if (is_enclosed(mesh, incidence, v)) {
        start = v;
        break;
      }
  }
  std::vector<CrackAdvance> advances;
  if (start < 0)
    return advances;
  for (const Vec2& direction : {Vec2(d), Vec2(-d)}) {
    if (auto advance = advance_crack(mesh, start, direction, settings))
      advances.push_back(std::move(*advance));
  }
  if (!advances.empty())
    append(advances.front().edit, start_edit);
  return advances;
}

PolylineCut cut_polyline(MembraneMesh& mesh, const std::vector<Vec2>& points,
                         const PropagationSettings& settings)
{
  PolylineCut cut;
  if (points.size() < 2)
    fail("a cut needs at least two points, got {}", points.size());
  int current = 0;
  for (int v = 1; v < mesh.node_count(); ++v)
    if ((mesh.rest[v] - points[0]).squaredNorm() < (mesh.rest[current] - points[0]).squaredNorm())
      current = v;
  const int start = current;
  const double reach = 0.5 * mean_edge_length(mesh);
  const int limit = 4 * mesh.triangle_count();
  bool open_end = true;
  for (std::size_t target = 1; target < points.size() && open_end; ++target) {
    while ((points[target] - mesh.rest[current]).norm() > reach) {
      const Vec2 d = (points[target] - mesh.rest[current]).normalized();
      auto advance = advance_crack(mesh, current, d, settings);
      if (!advance || static_cast<int>(cut.advances.size()) > limit)
        fail("the cut towards ({}, {}) mm cannot advance from node {} at ({}, {}) mm",
             points[target].x(), points[target].y(), current, mesh.rest[current].x(),
             mesh.rest[current].y());
      current = advance->to;
      open_end = advance->continues;
      cut.advances.push_back(std::move(*advance));
      if (!open_end)
        break;
    }
  }
  if (cut.advances.empty())
    fail("the cut from ({}, {}) mm is shorter than half an element", points[0].x(), points[0].y());
  const NodeIncidence incidence = build_incidence(mesh);
  const CrackAdvance& first = cut.advances.front();
  const CrackAdvance& last = cut.advances.back();
  if (is_enclosed(mesh, incidence, start)) {
    cut.start_node = start;
    cut.start_direction = (first.from_rest - first.to_rest).normalized();
  }
  if (last.continues) {
    cut.end_node = last.to;
    cut.end_direction = (last.to_rest - last.from_rest).normalized();
  }
  return cut;
}

} // namespace ligsim::membrane
