#pragma once
/// @brief Plain mesh data shared by the stages and the simulator (no behaviour, no file formats).

#include <Eigen/Core>

namespace ligsim {

/// Row-major so that a row (one point, one element) is contiguous, as in VTK's arrays.
using Points = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using Triangles = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;
using Tetrahedra = Eigen::Matrix<int, Eigen::Dynamic, 4, Eigen::RowMajor>;

/// A triangle surface: V (#V x 3, mm), F (#F x 3 vertex indices, counter-clockwise seen
/// from outside for a closed surface).
struct TriangleSurface {
  Points V;
  Triangles F;
};

/// A linear tetrahedral mesh: V (#V x 3, mm), T (#T x 4 vertex indices, positive orientation:
/// (v1 - v0) . ((v2 - v0) x (v3 - v0)) > 0).
struct TetMesh {
  Points V;
  Tetrahedra T;
};

} // namespace ligsim
