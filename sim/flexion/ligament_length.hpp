#pragma once
/// @brief The ligament's length from footprint to footprint: its centerline (from the build's
/// centerline stage) embedded in the rest tets, so that it deforms with them.

#include "common/mesh.hpp"

#include <Eigen/Core>

#include <vector>

namespace ligsim::sim {

class EmbeddedPolyline {
public:
  /// Finds each point of `polyline` (#P x 3, mm) in `mesh`'s tets; a point outside every tet (a
  /// centerline end on the surface, within round-off) takes the tet whose barycentric
  /// coordinates it misses least, clamped to it. Throws InputError for fewer than 2 points.
  EmbeddedPolyline(const TetMesh& mesh, const Points& polyline);

  /// The polyline's length with the mesh's nodes at `x` (flat, mm).
  double length(const Eigen::VectorXd& x) const;
  /// The largest distance of a point from the tet it was embedded in (0 inside), mm.
  double largest_miss_mm() const { return m_largest_miss_mm; }

private:
  struct Embedded {
    Eigen::Vector4i nodes;
    Eigen::Vector4d weights;
  };
  std::vector<Embedded> m_points;
  double m_largest_miss_mm = 0.0;
};

} // namespace ligsim::sim
