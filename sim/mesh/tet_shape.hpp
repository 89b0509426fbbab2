#pragma once
/// @brief Rest shape of linear tetrahedra: shape vectors D_i and volume V0 (paper eq. 1-4).

#include "common/mesh.hpp"

#include <Eigen/Core>

#include <vector>

namespace ligsim::sim {

/// Rest shape of one tet. Row i of D is the shape vector D_i, the gradient of node i's
/// barycentric coordinate in the rest shape (1/mm): eq. 1 with its 1/(6 V0) factor, so that
/// sum_i D_i = 0 and sum_i P_i (outer) D_i = I, and the deformation gradient is
/// sum_i Q_i (outer) D_i (eq. 2).
struct TetShape {
  Eigen::Matrix<double, 4, 3, Eigen::RowMajor> D;
  double V0 = 0.0; ///< rest volume, mm^3
};

/// Node positions of one tet, row i = node i (mm).
using TetCorners = Eigen::Matrix<double, 4, 3, Eigen::RowMajor>;

/// Corners of element `e` taken from `positions` (#nodes x 3, or a flat 3 #nodes vector).
template <class PositionsT>
TetCorners tet_corners(const Tetrahedra& T, Eigen::Index e, const PositionsT& positions)
{
  TetCorners Q;
  for (int i = 0; i < 4; ++i)
    for (int a = 0; a < 3; ++a)
      Q(i, a) = positions(3 * T(e, i) + a);
  return Q;
}

/// Shape of one tet from its rest corners. V0 is signed (negative when inverted).
TetShape tet_shape(const TetCorners& P);

/// Checks `mesh` (finite coordinates, node indices in range, every element positively oriented
/// and not degenerate) and returns the rest shape of every element. Throws InputError naming
/// the first offending node or element and the cause.
std::vector<TetShape> compute_rest_shapes(const TetMesh& mesh);

/// Where node `i` of element `e` goes, moved along the normal of its opposite face, for the
/// element to keep `volume_fraction` of its volume (its height above that face scales by it):
/// how the stability suites make slivers.
Eigen::Vector3d toward_opposite_face(const TetMesh& mesh, Eigen::Index e, int i,
                                     double volume_fraction);

} // namespace ligsim::sim
