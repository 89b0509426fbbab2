#pragma once
/// @brief Stage 6: fiber orientation per tetrahedron (paper section 3.2).

#include "common/mesh.hpp"
#include "stages/geometry/grid.hpp"

#include <Eigen/Core>

namespace ligsim {
class Polyline;
}

namespace ligsim::fibers {

/// The fiber direction at points of the shape: the centerline tangent at the closest
/// centerline point C(x), with its component along grad D removed, normalised.
class FiberField {
public:
  /// `field` is D on the inside voxels of `mask`; its gradient is taken by finite differences
  /// between inside voxels (when asked for, not stored: the grids stay sparse) and interpolated
  /// trilinearly.
  FiberField(const Polyline& centerline, ScalarGrid field, Mask mask);

  struct Sample {
    Eigen::Vector3d direction; ///< unit fiber direction
    Eigen::Vector3d gradient;  ///< grad D at the point, 1/mm
    bool projected;            ///< false where grad D vanishes or is parallel to the tangent:
                               ///< the tangent itself is returned
  };
  Sample at(const Eigen::Vector3d& x) const;
  /// The centerline tangent at the closest centerline point.
  Eigen::Vector3d tangent_at(const Eigen::Vector3d& x) const;

private:
  /// grad D at an inside voxel centre, 1/mm; zero outside.
  Eigen::Vector3d gradient_at_voxel(const Eigen::Vector3i& v) const;

  const Polyline& m_centerline;
  ScalarGrid m_field;
  Mask m_mask;
};

struct Parameters {
  /// Samples per tetrahedron: 1 (centroid), 4 (the 4-point Gauss points) or 5 (both).
  int samples_per_tet = 5;
};

struct Result {
  Eigen::MatrixX3d directions;     ///< #T x 3 unit vectors, one per tetrahedron
  int unprojected_samples = 0;     ///< samples where grad D gave no isosurface (tangent used)
  double mean_alignment_deg = 0.0; ///< mean angle between a tet's fiber and the centerline tangent
};

/// Averages the fiber samples inside each tetrahedron (signs aligned with the tangent first,
/// since a fiber has no sense) and normalises.
Result per_tet_directions(const TetMesh& mesh, const FiberField& fibers,
                          const Parameters& parameters);

} // namespace ligsim::fibers
