#include "sim/contact/winding_number.hpp"

#include <algorithm>
#include <cmath>

namespace ligsim::sim {

namespace {

constexpr int kLeafTriangles = 8;

} // namespace

WindingNumber::WindingNumber(const TriangleSurface& surface, double accuracy)
    : m_surface(surface)
    , m_accuracy(accuracy)
{
  m_order.resize(static_cast<std::size_t>(surface.F.rows()));
  for (std::size_t f = 0; f < m_order.size(); ++f)
    m_order[f] = static_cast<int>(f);
  for (Eigen::Index v = 0; v < surface.V.rows(); ++v)
    m_bounds.extend(Eigen::Vector3d(surface.V.row(v)));
  if (!m_order.empty())
    build(0, static_cast<int>(m_order.size()));
}

/// Node of m_order[first, first + count): split at the median of the longest axis of the
/// triangles' centroids.
int WindingNumber::build(int first, int count)
{
  const int index = static_cast<int>(m_nodes.size());
  m_nodes.emplace_back();
  Node node;
  node.first = first;
  node.count = count;
  double area = 0.0;
  Eigen::AlignedBox3d box;
  const auto corner = [&](int f, int k) {
    return Eigen::Vector3d(m_surface.V.row(m_surface.F(f, k)));
  };
  for (int i = first; i < first + count; ++i) {
    const int f = m_order[static_cast<std::size_t>(i)];
    const Eigen::Vector3d a = corner(f, 0), b = corner(f, 1), c = corner(f, 2);
    const Eigen::Vector3d area_vector = 0.5 * (b - a).cross(c - a);
    node.dipole += area_vector;
    area += area_vector.norm();
    node.centre += area_vector.norm() * (a + b + c) / 3.0;
    box.extend((a + b + c) / 3.0);
  }
  node.centre = area > 0.0 ? Eigen::Vector3d(node.centre / area) : box.center();
  for (int i = first; i < first + count; ++i) {
    const int f = m_order[static_cast<std::size_t>(i)];
    const Eigen::Vector3d a = corner(f, 0), b = corner(f, 1), c = corner(f, 2);
    node.moment += 0.5 * (b - a).cross(c - a) * ((a + b + c) / 3.0 - node.centre).transpose();
    for (int k = 0; k < 3; ++k)
      node.radius = std::max(node.radius, (corner(f, k) - node.centre).norm());
  }
  if (count > kLeafTriangles) {
    int axis = 0;
    box.sizes().maxCoeff(&axis);
    const auto begin = m_order.begin() + first, middle = begin + count / 2;
    std::nth_element(begin, middle, begin + count, [&](int f, int g) {
      return corner(f, 0)[axis] + corner(f, 1)[axis] + corner(f, 2)[axis] <
             corner(g, 0)[axis] + corner(g, 1)[axis] + corner(g, 2)[axis];
    });
    node.left = build(first, count / 2);
    node.right = build(first + count / 2, count - count / 2);
  }
  m_nodes[static_cast<std::size_t>(index)] = node;
  return index;
}

/// Signed solid angle of triangle f at p (van Oosterom and Strackee 1983), positive when p
/// lies behind it (on the side its normal points away from).
double WindingNumber::triangle_solid_angle(int f, const Eigen::Vector3d& p) const
{
  const Eigen::Vector3d a = Eigen::Vector3d(m_surface.V.row(m_surface.F(f, 0))) - p;
  const Eigen::Vector3d b = Eigen::Vector3d(m_surface.V.row(m_surface.F(f, 1))) - p;
  const Eigen::Vector3d c = Eigen::Vector3d(m_surface.V.row(m_surface.F(f, 2))) - p;
  const double la = a.norm(), lb = b.norm(), lc = c.norm();
  const double numerator = a.dot(b.cross(c));
  const double denominator = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
  return 2.0 * std::atan2(numerator, denominator);
}

double WindingNumber::exact(const Eigen::Vector3d& p) const
{
  double sum = 0.0;
  for (Eigen::Index f = 0; f < m_surface.F.rows(); ++f)
    sum += triangle_solid_angle(static_cast<int>(f), p);
  return sum / (4.0 * M_PI);
}

double WindingNumber::operator()(const Eigen::Vector3d& p) const
{
  if (m_nodes.empty())
    return 0.0;
  double sum = 0.0;
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = m_nodes[static_cast<std::size_t>(stack[--top])];
    const Eigen::Vector3d r = node.centre - p;
    const double distance = r.norm();
    if (distance > m_accuracy * node.radius) {
      // Far: the solid angle of the area vectors a at x = centre + d, a . (x - p) / |x - p|^3,
      // to first order in d: N . r / |r|^3 + M : (I / |r|^3 - 3 r r^T / |r|^5), r = centre - p.
      const double r3 = distance * distance * distance;
      sum += node.dipole.dot(r) / r3 + node.moment.trace() / r3 -
             3.0 * r.dot(node.moment * r) / (r3 * distance * distance);
    } else if (node.left < 0) {
      for (int i = node.first; i < node.first + node.count; ++i)
        sum += triangle_solid_angle(m_order[static_cast<std::size_t>(i)], p);
    } else {
      stack[top++] = node.left;
      stack[top++] = node.right;
    }
  }
  return sum / (4.0 * M_PI);
}

} // namespace ligsim::sim
