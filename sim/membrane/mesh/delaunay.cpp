#include "sim/membrane/mesh/delaunay.hpp"

#include "common/error.hpp"

#include <algorithm>
#include <map>
#include <utility>

namespace ligsim::membrane {
namespace {

struct Candidate {
  Triangle nodes;
  Vec2 centre;
  double radius_squared;
};

Candidate make_candidate(const std::vector<Vec2>& p, const Triangle& t)
{
  const Vec2 &a = p[t[0]], &b = p[t[1]], &c = p[t[2]];
  const double d = 2.0 * cross(b - a, c - a);
  const Vec2 ab = b - a, ac = c - a;
  const Vec2 offset(ac.y() * ab.squaredNorm() - ab.y() * ac.squaredNorm(),
                    ab.x() * ac.squaredNorm() - ac.x() * ab.squaredNorm());
  const Vec2 centre = a + offset / d;
  return {t, centre, (centre - a).squaredNorm()};
}

/// Area of the convex hull of `points` (monotone chain).
double hull_area(std::vector<Vec2> points)
{
  std::sort(points.begin(), points.end(), [](const Vec2& a, const Vec2& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  std::vector<Vec2> hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && cross(hull[k - 1] - hull[k - 2], points[i] - hull[k - 2]) <= 0)
      --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 1] - hull[k - 2], points[i] - hull[k - 2]) <= 0)
      --k;
    hull[k++] = points[i];
  }
  double area = 0.0;
  for (std::size_t i = 0; i + 1 < k; ++i)
    area += 0.5 * cross(hull[i], hull[i + 1]);
  return area;
}

} // namespace

std::vector<Triangle> delaunay_triangulation(const std::vector<Vec2>& input)
{
  if (input.size() < 3)
    fail<SolverError>("Delaunay triangulation needs at least 3 points, got {}", input.size());
  Vec2 low = input[0], high = input[0];
  for (const Vec2& p : input) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  const Vec2 middle = 0.5 * (low + high);
  const double size = std::max(1e-12, (high - low).maxCoeff());

  // A super-triangle far around the points; its corners are the last three points.
  std::vector<Vec2> points = input;
  const int n = static_cast<int>(input.size());
  points.push_back(middle + Vec2(-1e3 * size, -1e3 * size));
  points.push_back(middle + Vec2(1e3 * size, -1e3 * size));
  points.push_back(middle + Vec2(0.0, 1e3 * size));
  std::vector<Candidate> triangles = {make_candidate(points, {n, n + 1, n + 2})};

  std::vector<Candidate> kept;
  std::map<std::pair<int, int>, int> cavity_edges; // directed edge -> count
  for (int i = 0; i < n; ++i) {
    const Vec2& p = points[i];
    kept.clear();
    cavity_edges.clear();
    for (const Candidate& t : triangles) {
      // Strictly inside, with a margin: points on a circumcircle (the cocircular boundary
      // nodes of a disc) count as outside, so rounding cannot make the cavity inconsistent.
      if ((p - t.centre).squaredNorm() < t.radius_squared * (1.0 - 1e-10)) {
        for (int k = 0; k < 3; ++k)
          ++cavity_edges[{t.nodes[k], t.nodes[(k + 1) % 3]}];
      } else {
        kept.push_back(t);
      }
    }
    for (const auto& [edge, count] : cavity_edges)
      if (!cavity_edges.count({edge.second, edge.first})) // on the cavity's boundary
        kept.push_back(make_candidate(points, {edge.first, edge.second, i}));
    triangles.swap(kept);
  }

  std::vector<Triangle> result;
  double area = 0.0;
  for (const Candidate& t : triangles) {
    if (t.nodes[0] >= n || t.nodes[1] >= n || t.nodes[2] >= n)
      continue;
    result.push_back(t.nodes);
    area += signed_area(input[t.nodes[0]], input[t.nodes[1]], input[t.nodes[2]]);
  }
  const double expected = hull_area(input);
  if (std::abs(area - expected) > 1e-9 * expected)
    fail<SolverError>("Delaunay triangulation covers {} of the hull's area {}", area, expected);
  return result;
}

} // namespace ligsim::membrane
