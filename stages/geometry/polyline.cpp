#include "stages/geometry/polyline.hpp"

#include "common/error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ligsim {

Polyline::Polyline(Points points, Points tangents)
    : m_points(std::move(points))
    , m_tangents(std::move(tangents))
{
  if (m_points.rows() < 2 || m_tangents.rows() != m_points.rows())
    fail("a centerline needs at least two points with a tangent each (got {} and {})",
         m_points.rows(), m_tangents.rows());
  m_arc.assign(static_cast<std::size_t>(m_points.rows()), 0.0);
  for (Eigen::Index i = 1; i < m_points.rows(); ++i)
    m_arc[i] = m_arc[i - 1] + (m_points.row(i) - m_points.row(i - 1)).norm();
}

Polyline::Projection Polyline::project(const Eigen::Vector3d& x) const
{
  // Every segment is tested: centerlines have a few hundred points, and a nearest-vertex
  // shortcut can pick the wrong segment where the line bends.
  Projection best{x, Eigen::Vector3d::UnitZ(), std::numeric_limits<double>::infinity(), 0.0};
  for (Eigen::Index i = 0; i + 1 < m_points.rows(); ++i) {
    const Eigen::Vector3d a = m_points.row(i), b = m_points.row(i + 1);
    const Eigen::Vector3d ab = b - a;
    const double length2 = ab.squaredNorm();
    const double s = length2 > 0.0 ? std::clamp((x - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
    const Eigen::Vector3d p = a + s * ab;
    const double d = (x - p).squaredNorm();
    if (d < best.distance) {
      best.distance = d;
      best.point = p;
      best.tangent = ((1 - s) * m_tangents.row(i) + s * m_tangents.row(i + 1)).transpose();
      best.arc_length = m_arc[i] + s * std::sqrt(length2);
    }
  }
  best.distance = std::sqrt(best.distance);
  best.tangent.normalize();
  return best;
}

} // namespace ligsim
