#include "pipeline/study/surface_variants.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <random>
#include <set>

namespace ligsim::study {

namespace {

/// Each vertex's neighbours along the triangles' edges.
std::vector<std::vector<int>> vertex_neighbours(const TriangleSurface& surface)
{
  std::vector<std::set<int>> sets(static_cast<std::size_t>(surface.V.rows()));
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = surface.F(f, k), b = surface.F(f, (k + 1) % 3);
      sets[static_cast<std::size_t>(a)].insert(b);
      sets[static_cast<std::size_t>(b)].insert(a);
    }
  std::vector<std::vector<int>> neighbours;
  for (const auto& s : sets)
    neighbours.emplace_back(s.begin(), s.end());
  return neighbours;
}

/// One umbrella step: each vertex moves `factor` of the way to its neighbours' mean.
Points umbrella_step(const Points& V, const std::vector<std::vector<int>>& neighbours,
                     double factor)
{
  Points moved = V;
  for (Eigen::Index v = 0; v < V.rows(); ++v) {
    const auto& n = neighbours[static_cast<std::size_t>(v)];
    if (n.empty())
      continue;
    Eigen::RowVector3d mean = Eigen::RowVector3d::Zero();
    for (int u : n)
      mean += V.row(u);
    mean /= static_cast<double>(n.size());
    moved.row(v) += factor * (mean - V.row(v));
  }
  return moved;
}

/// Geodesic distance along the edges from the `sources` (Dijkstra).
std::vector<double> edge_distance(const TriangleSurface& surface,
                                  const std::vector<std::vector<int>>& neighbours,
                                  const std::vector<int>& sources)
{
  std::vector<double> distance(static_cast<std::size_t>(surface.V.rows()),
                               std::numeric_limits<double>::infinity());
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  for (int s : sources) {
    distance[static_cast<std::size_t>(s)] = 0.0;
    queue.push({0.0, s});
  }
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > distance[static_cast<std::size_t>(v)])
      continue;
    for (int u : neighbours[static_cast<std::size_t>(v)]) {
      const double next = d + (surface.V.row(u) - surface.V.row(v)).norm();
      if (next < distance[static_cast<std::size_t>(u)]) {
        distance[static_cast<std::size_t>(u)] = next;
        queue.push({next, u});
      }
    }
  }
  return distance;
}

} // namespace

Points vertex_normals(const TriangleSurface& surface)
{
  Points normals = Points::Zero(surface.V.rows(), 3);
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f) {
    const Eigen::Vector3d a = surface.V.row(surface.F(f, 0)).transpose();
    const Eigen::Vector3d b = surface.V.row(surface.F(f, 1)).transpose();
    const Eigen::Vector3d c = surface.V.row(surface.F(f, 2)).transpose();
    const Eigen::RowVector3d area_normal = 0.5 * (b - a).cross(c - a).transpose();
    for (int k = 0; k < 3; ++k)
      normals.row(surface.F(f, k)) += area_normal;
  }
  for (Eigen::Index v = 0; v < normals.rows(); ++v)
    if (normals.row(v).norm() > 0.0)
      normals.row(v).normalize();
  return normals;
}

TriangleSurface offset_surface(const TriangleSurface& surface, double distance_mm)
{
  TriangleSurface moved = surface;
  moved.V += distance_mm * vertex_normals(surface);
  return moved;
}

TriangleSurface smooth_surface(const TriangleSurface& surface, int iterations)
{
  const auto neighbours = vertex_neighbours(surface);
  TriangleSurface smoothed = surface;
  for (int i = 0; i < iterations; ++i) {
    smoothed.V = umbrella_step(smoothed.V, neighbours, 0.5);
    smoothed.V = umbrella_step(smoothed.V, neighbours, -0.53);
  }
  return smoothed;
}

TriangleSurface roughen_surface(const TriangleSurface& surface, double rms_mm, int passes,
                                unsigned seed)
{
  const auto neighbours = vertex_neighbours(surface);
  std::mt19937 random(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  Points noise = Points::Zero(surface.V.rows(), 3);
  for (Eigen::Index v = 0; v < noise.rows(); ++v)
    noise(v, 0) = normal(random);
  for (int i = 0; i < passes; ++i)
    noise = umbrella_step(noise, neighbours, 1.0);
  const Eigen::VectorXd field =
      noise.col(0) - Eigen::VectorXd::Constant(noise.rows(), noise.col(0).mean());
  const double rms = std::sqrt(field.squaredNorm() / static_cast<double>(field.size()));
  TriangleSurface rough = surface;
  const Points normals = vertex_normals(surface);
  for (Eigen::Index v = 0; v < rough.V.rows(); ++v)
    rough.V.row(v) += (rms > 0.0 ? rms_mm * field(v) / rms : 0.0) * normals.row(v);
  return rough;
}

std::vector<int> grow_area(const TriangleSurface& surface, const std::vector<int>& area,
                           double distance_mm)
{
  const auto neighbours = vertex_neighbours(surface);
  std::vector<int> result;
  if (distance_mm >= 0.0) {
    const std::vector<double> d = edge_distance(surface, neighbours, area);
    for (std::size_t v = 0; v < d.size(); ++v)
      if (d[v] <= distance_mm)
        result.push_back(static_cast<int>(v));
    return result;
  }
  std::vector<bool> inside(static_cast<std::size_t>(surface.V.rows()), false);
  for (int v : area)
    inside[static_cast<std::size_t>(v)] = true;
  std::vector<int> outside;
  for (std::size_t v = 0; v < inside.size(); ++v)
    if (!inside[v])
      outside.push_back(static_cast<int>(v));
  const std::vector<double> d = edge_distance(surface, neighbours, outside);
  for (int v : area)
    if (d[static_cast<std::size_t>(v)] > -distance_mm)
      result.push_back(v);
  return result;
}

} // namespace ligsim::study
