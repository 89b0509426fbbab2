#include "sim/contact/distance_field.hpp"

#include "common/error.hpp"

namespace ligsim::sim {

PlaneDistance::PlaneDistance(const Eigen::Vector3d& point_mm, const Eigen::Vector3d& normal)
    : m_point(point_mm)
    , m_normal(normal.normalized())
{
  if (!(normal.norm() > 0.0) || !normal.allFinite())
    fail("contact plane: the normal must be a non-zero vector");
}

DistanceSample PlaneDistance::sample(const Eigen::Vector3d& p_mm, bool) const
{
  DistanceSample s;
  s.distance_mm = m_normal.dot(p_mm - m_point);
  s.gradient = m_normal;
  return s;
}

CylinderDistance::CylinderDistance(const Eigen::Vector3d& point_mm, const Eigen::Vector3d& axis,
                                   double radius_mm)
    : m_point(point_mm)
    , m_axis(axis.normalized())
    , m_radius(radius_mm)
{
  if (!(axis.norm() > 0.0) || !axis.allFinite())
    fail("contact cylinder: the axis must be a non-zero vector");
  if (!(radius_mm > 0.0))
    fail("contact cylinder: the radius must be positive, got {}", radius_mm);
}

DistanceSample CylinderDistance::sample(const Eigen::Vector3d& p_mm, bool with_hessian) const
{
  const Eigen::Vector3d offset = p_mm - m_point;
  const Eigen::Vector3d radial = offset - m_axis.dot(offset) * m_axis;
  const double r = radial.norm();
  DistanceSample s;
  s.distance_mm = r - m_radius;
  if (r == 0.0)
    return s; // on the axis: no direction; the gradient stays zero
  const Eigen::Vector3d n = radial / r;
  s.gradient = n;
  if (with_hessian) // d n / d p = (I - a a^T - n n^T) / r
    s.hessian = (Eigen::Matrix3d::Identity() - m_axis * m_axis.transpose() - n * n.transpose()) / r;
  return s;
}

} // namespace ligsim::sim
