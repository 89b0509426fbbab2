#pragma once
/// @brief Closest points on a polyline (the centerline), with the tangent there.

#include "common/mesh.hpp"

#include <Eigen/Core>

namespace ligsim {

class Polyline {
public:
  /// `points` (#P x 3, mm, #P >= 2) in order; `tangents` (#P x 3 unit vectors) at the points.
  Polyline(Points points, Points tangents);

  struct Projection {
    Eigen::Vector3d point;   ///< closest point on the polyline, mm
    Eigen::Vector3d tangent; ///< unit tangent there (interpolated between the vertices)
    double distance;         ///< mm
    double arc_length;       ///< from the first point, mm
  };
  Projection project(const Eigen::Vector3d& x) const;

  const Points& points() const { return m_points; }
  const Points& tangents() const { return m_tangents; }
  double length() const { return m_arc.back(); }

private:
  Points m_points;
  Points m_tangents;
  std::vector<double> m_arc;
};

} // namespace ligsim
