#pragma once
/// @brief A signed distance to a rigid obstacle in its own (rest) frame, positive outside, with
/// its gradient and Hessian: analytic shapes for tests, a level-set grid for bones.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>

namespace ligsim::sim {

struct DistanceSample {
  double distance_mm = 0.0;
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
  Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero(); ///< 1/mm; filled only when asked for
};

class DistanceField {
public:
  virtual ~DistanceField() = default;
  virtual DistanceSample sample(const Eigen::Vector3d& p_mm, bool with_hessian) const = 0;
  /// A lower bound of the distance (or the distance itself), cheap: culls far points. The
  /// default samples.
  virtual double distance_bound(const Eigen::Vector3d& p_mm) const
  {
    return sample(p_mm, false).distance_mm;
  }
  /// The largest value distance_bound() gives (the grid's band): farther is never told apart.
  virtual double bound_limit_mm() const { return INFINITY; }
  /// The box outside which every point is at least `far_mm` away (the grid's band), so that
  /// points outside it need no sample. Empty: no such box (analytic shapes).
  virtual Eigen::AlignedBox3d near_box() const { return {}; }
  /// Largest |gradient| of the field: the conservative step bound divides by it.
  virtual double lipschitz() const { return 1.0; }
};

/// The half-space above the plane through `point_mm` with unit `normal` (outside = along it).
class PlaneDistance final : public DistanceField {
public:
  PlaneDistance(const Eigen::Vector3d& point_mm, const Eigen::Vector3d& normal);
  DistanceSample sample(const Eigen::Vector3d& p_mm, bool with_hessian) const override;

private:
  Eigen::Vector3d m_point;
  Eigen::Vector3d m_normal;
};

/// An infinite solid cylinder of radius `radius_mm` about the line through `point_mm` along
/// unit `axis`.
class CylinderDistance final : public DistanceField {
public:
  CylinderDistance(const Eigen::Vector3d& point_mm, const Eigen::Vector3d& axis, double radius_mm);
  DistanceSample sample(const Eigen::Vector3d& p_mm, bool with_hessian) const override;

private:
  Eigen::Vector3d m_point;
  Eigen::Vector3d m_axis;
  double m_radius = 1.0;
};

} // namespace ligsim::sim
