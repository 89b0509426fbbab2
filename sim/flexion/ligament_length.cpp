#include "sim/flexion/ligament_length.hpp"

#include "common/error.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <limits>

namespace ligsim::sim {

namespace {

/// Barycentric coordinates of p in the tet (a, b, c, d).
Eigen::Vector4d barycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                            const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                            const Eigen::Vector3d& d)
{
  Eigen::Matrix3d edges;
  edges << b - a, c - a, d - a;
  const Eigen::Vector3d bcd = edges.partialPivLu().solve(p - a);
  return {1.0 - bcd.sum(), bcd.x(), bcd.y(), bcd.z()};
}

} // namespace

EmbeddedPolyline::EmbeddedPolyline(const TetMesh& mesh, const Points& polyline)
{
  if (polyline.rows() < 2)
    fail("ligament length: the centerline has {} points; at least 2 are needed", polyline.rows());
  const Eigen::Index tets = mesh.T.rows();
  std::vector<Eigen::AlignedBox3d> boxes(static_cast<std::size_t>(tets));
  for (Eigen::Index t = 0; t < tets; ++t)
    for (int k = 0; k < 4; ++k)
      boxes[static_cast<std::size_t>(t)].extend(mesh.V.row(mesh.T(t, k)).transpose());
  for (Eigen::Index i = 0; i < polyline.rows(); ++i) {
    const Eigen::Vector3d p = polyline.row(i).transpose();
    double best_miss = std::numeric_limits<double>::infinity();
    Embedded best{};
    for (Eigen::Index t = 0; t < tets; ++t) {
      // A point within 1 mm of a tet's box is a candidate: the nearest tet of an end point.
      if (boxes[static_cast<std::size_t>(t)].exteriorDistance(p) > 1.0)
        continue;
      const Eigen::Vector4i nodes = mesh.T.row(t).transpose();
      const Eigen::Vector4d w = barycentric(p, mesh.V.row(nodes(0)), mesh.V.row(nodes(1)),
                                            mesh.V.row(nodes(2)), mesh.V.row(nodes(3)));
      const double miss = std::max(0.0, -w.minCoeff());
      if (miss < best_miss) {
        best_miss = miss;
        best = {nodes, w};
      }
      if (miss == 0.0)
        break;
    }
    if (!std::isfinite(best_miss))
      fail("ligament length: centerline point {} ({:.2f}, {:.2f}, {:.2f}) mm lies more than 1 mm "
           "from every tet",
           i, p.x(), p.y(), p.z());
    if (best_miss > 0.0) {
      best.weights = best.weights.cwiseMax(0.0);
      best.weights /= best.weights.sum();
      Eigen::Vector3d q = Eigen::Vector3d::Zero();
      for (int k = 0; k < 4; ++k)
        q += best.weights(k) * mesh.V.row(best.nodes(k)).transpose();
      m_largest_miss_mm = std::max(m_largest_miss_mm, (q - p).norm());
    }
    m_points.push_back(best);
  }
}

double EmbeddedPolyline::length(const Eigen::VectorXd& x) const
{
  double total = 0.0;
  Eigen::Vector3d previous = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < m_points.size(); ++i) {
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (int k = 0; k < 4; ++k)
      p += m_points[i].weights(k) * x.segment<3>(3 * m_points[i].nodes(k));
    if (i > 0)
      total += (p - previous).norm();
    previous = p;
  }
  return total;
}

} // namespace ligsim::sim
