#include "sim/membrane/mesh/membrane_mesh.hpp"

#include <algorithm>
#include <cmath>

namespace ligsim::membrane {

int MembraneMesh::add_node(const Vec2& rest_position)
{
  rest.push_back(rest_position);
  position.push_back(rest_position);
  velocity.push_back(Vec2::Zero());
  last_velocity_change.push_back(Vec2::Zero());
  mass.push_back(0.0);
  constraint.push_back(NodeConstraint::free);
  prescribed_velocity.push_back(Vec2::Zero());
  return node_count() - 1;
}

int MembraneMesh::add_node_between(int b, int c, double t)
{
  const auto lerp = [t](const Vec2& p, const Vec2& q) -> Vec2 { return (1.0 - t) * p + t * q; };
  const int n = add_node(lerp(rest[b], rest[c]));
  position[n] = lerp(position[b], position[c]);
  velocity[n] = lerp(velocity[b], velocity[c]);
  last_velocity_change[n] = lerp(last_velocity_change[b], last_velocity_change[c]);
  if (constraint[b] == NodeConstraint::prescribed && constraint[c] == NodeConstraint::prescribed) {
    constraint[n] = NodeConstraint::prescribed;
    prescribed_velocity[n] = lerp(prescribed_velocity[b], prescribed_velocity[c]);
  }
  return n;
}

int MembraneMesh::add_node_at_centroid(int tri)
{
  const Triangle t = triangles[tri];
  const auto mean = [&](const std::vector<Vec2>& values) -> Vec2 {
    return (values[t[0]] + values[t[1]] + values[t[2]]) / 3.0;
  };
  const int n = add_node(mean(rest));
  position[n] = mean(position);
  velocity[n] = mean(velocity);
  last_velocity_change[n] = mean(last_velocity_change);
  if (std::all_of(t.begin(), t.end(),
                  [&](int v) { return constraint[v] == NodeConstraint::prescribed; })) {
    constraint[n] = NodeConstraint::prescribed;
    prescribed_velocity[n] = mean(prescribed_velocity);
  }
  return n;
}

int MembraneMesh::add_node_copy(int v)
{
  const int n = add_node(rest[v]);
  position[n] = position[v];
  velocity[n] = velocity[v];
  last_velocity_change[n] = last_velocity_change[v];
  constraint[n] = constraint[v];
  prescribed_velocity[n] = prescribed_velocity[v];
  return n;
}

int MembraneMesh::add_triangle(const Triangle& nodes, double fiber_angle,
                               const std::array<bool, 3>& cut,
                               const std::array<std::uint8_t, 3>& load)
{
  triangles.push_back(nodes);
  fiber_angle_rad.push_back(fiber_angle);
  side_cut.push_back(cut);
  side_load.push_back(load);
  return triangle_count() - 1;
}

NodeIncidence build_incidence(const MembraneMesh& mesh)
{
  NodeIncidence incidence;
  incidence.offset.assign(mesh.node_count() + 1, 0);
  for (const Triangle& t : mesh.triangles)
    for (int v : t)
      ++incidence.offset[v + 1];
  for (int v = 0; v < mesh.node_count(); ++v)
    incidence.offset[v + 1] += incidence.offset[v];
  incidence.triangle.resize(incidence.offset.back());
  std::vector<int> fill(incidence.offset.begin(), incidence.offset.end() - 1);
  for (int tri = 0; tri < mesh.triangle_count(); ++tri)
    for (int v : mesh.triangles[tri])
      incidence.triangle[fill[v]++] = tri;
  return incidence;
}

double signed_area(const Vec2& a, const Vec2& b, const Vec2& c)
{
  return 0.5 * cross(b - a, c - a);
}

double rest_area(const MembraneMesh& mesh, int tri)
{
  const Triangle& t = mesh.triangles[tri];
  return signed_area(mesh.rest[t[0]], mesh.rest[t[1]], mesh.rest[t[2]]);
}

double min_angle(const Vec2& a, const Vec2& b, const Vec2& c)
{
  const auto angle = [](const Vec2& p, const Vec2& q, const Vec2& r) {
    const Vec2 u = q - p, w = r - p;
    return std::atan2(std::abs(cross(u, w)), u.dot(w));
  };
  return std::min({angle(a, b, c), angle(b, c, a), angle(c, a, b)});
}

double min_rest_angle(const MembraneMesh& mesh)
{
  double smallest = M_PI;
  for (const Triangle& t : mesh.triangles)
    smallest = std::min(smallest, min_angle(mesh.rest[t[0]], mesh.rest[t[1]], mesh.rest[t[2]]));
  return smallest;
}

void update_lumped_masses(MembraneMesh& mesh, const NodeIncidence& incidence,
                          double areal_density_t_per_mm2, const std::vector<int>& nodes)
{
  for (int v : nodes) {
    double area = 0.0;
    for (const int* tri = incidence.begin(v); tri != incidence.end(v); ++tri)
      area += rest_area(mesh, *tri);
    mesh.mass[v] = areal_density_t_per_mm2 * area / 3.0;
  }
}

std::vector<std::array<int, 2>> crack_edges(const MembraneMesh& mesh)
{
  std::vector<std::array<int, 2>> edges;
  for (int tri = 0; tri < mesh.triangle_count(); ++tri)
    for (int k = 0; k < 3; ++k)
      if (mesh.side_cut[tri][k])
        edges.push_back({mesh.triangles[tri][k], mesh.triangles[tri][(k + 1) % 3]});
  return edges;
}

} // namespace ligsim::membrane
