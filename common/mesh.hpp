#pragma once
/// @brief Plain mesh data shared by the stages and the simulator (no behaviour, no file formats).

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <vector>

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

/// Nodes of each element: the corners 0-3, then the mid-edge nodes of the edges
/// (0,1), (1,2), (2,0), (0,3), (1,3), (2,3), FEBio's tet10 and VTK_QUADRATIC_TETRA order.
using QuadraticTetrahedra = Eigen::Matrix<int, Eigen::Dynamic, 10, Eigen::RowMajor>;

/// The corners of the edge that each mid-edge node 4-9 sits on.
inline constexpr std::array<std::array<int, 2>, 6> kQuadraticTetEdges = {
    {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}}};

/// A quadratic tet mesh: V (#V x 3, mm), T (#T x 10 node indices, corners positively oriented).
struct QuadraticTetMesh {
  Points V;
  QuadraticTetrahedra T;
};

/// A curve on a surface that a mesh is to keep as a chain of its edges (a feature), as the
/// points of a polyline, mm; closed when its first point equals its last.
using FeatureLine = std::vector<Eigen::Vector3d>;

/// A mesh's mean element size, (volume / elements)^(1/3): how the companion's size search and
/// the flexion's error estimate compare two meshes of one ligament.
inline double mean_element_size(double volume_mm3, double elements)
{
  return std::cbrt(volume_mm3 / elements);
}

} // namespace ligsim
