#pragma once
/// @brief How deep points lie inside a bone's triangles, independently of its contact grid:
/// inside by the generalized winding number (|w| >= 1/2: right on several shells, flipped shells
/// and small holes, where the sign of the nearest triangle's normal is not), depth the distance
/// to the nearest triangle.

#include "common/mesh.hpp"
#include "sim/contact/triangle_distance.hpp"
#include "sim/contact/winding_number.hpp"

namespace ligsim::sim {

class BonePenetration {
public:
  /// `bone`: triangles, mm (kept).
  explicit BonePenetration(const TriangleSurface& bone);

  /// 0 for a point outside the bone (no work outside its bounding box), else its distance to
  /// the bone's triangles, mm.
  double depth_mm(const Eigen::Vector3d& p) const;

private:
  WindingNumber m_winding;
  TriangleDistance m_distance;
};

} // namespace ligsim::sim
