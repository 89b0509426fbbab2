#pragma once
/// @brief 10-node (quadratic) tetrahedra: meshes, shape functions, quadrature rules and the rest
/// shape at each quadrature point.

#include "common/mesh.hpp"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace ligsim::sim {

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

/// Positions or shape-function gradients of one element's 10 nodes, row i = node i.
using QuadraticTetRows = Eigen::Matrix<double, 10, 3, Eigen::RowMajor>;

/// A symmetric rule on the reference tet: barycentric points (l0, l1, l2, l3) and weights that
/// sum to one (the fraction of a straight-sided element's volume each point stands for).
struct QuadratureRule {
  int degree = 0; ///< polynomials up to this degree are integrated exactly
  std::vector<Eigen::Vector4d> points;
  std::vector<double> weights;
};

/// The rule of the given degree: 1 (the centroid), 2 (4 points) or 5 (Keast's 15 points, every
/// weight positive). Throws InputError for another degree.
QuadratureRule tet_quadrature(int degree);

/// Shape functions N_i at barycentric point `l` (corners l_i (2 l_i - 1), mid-edge 4 l_i l_j).
Eigen::Matrix<double, 10, 1> quadratic_shape_functions(const Eigen::Vector4d& l);

/// Their derivatives with respect to the reference coordinates (l1, l2, l3), l0 = 1 - l1 - l2 - l3.
QuadraticTetRows quadratic_shape_derivatives(const Eigen::Vector4d& l);

/// The rest shape of one element at one quadrature point: G (row i: the gradient of N_i in the
/// rest shape, 1/mm), and the volume the point stands for (mm^3).
struct QuadraturePointShape {
  QuadraticTetRows G;
  double weight = 0.0;
  double det_j = 0.0; ///< det dX/d(l1, l2, l3), mm^3; not positive where the element folds
};

/// The rest shape of one element at every point of `rule`.
struct QuadraticTetShape {
  std::vector<QuadraturePointShape> points;
  double V0 = 0.0; ///< rest volume, mm^3
};

/// Node positions of element `e` taken from `positions` (#nodes x 3, or a flat 3 #nodes vector).
template <class PositionsT>
QuadraticTetRows quadratic_tet_nodes(const QuadraticTetrahedra& T, Eigen::Index e,
                                     const PositionsT& positions)
{
  QuadraticTetRows Q;
  for (int i = 0; i < 10; ++i)
    for (int a = 0; a < 3; ++a)
      Q(i, a) = positions(3 * T(e, i) + a);
  return Q;
}

/// The shape of one element with rest nodes `X` (mm) at the points of `rule`.
QuadraticTetShape quadratic_tet_shape(const QuadraticTetRows& X, const QuadratureRule& rule);

/// Checks `mesh` (finite coordinates, node indices in range, det dX/dl positive at every
/// quadrature point and at every corner) and returns every element's rest shape. Throws
/// InputError naming the first offending node or element and the cause.
std::vector<QuadraticTetShape> compute_rest_shapes(const QuadraticTetMesh& mesh,
                                                   const QuadratureRule& rule);

/// The linear mesh with a node added at the middle of every edge (shared by the elements around
/// it). The linear nodes keep their indices; the mid-edge nodes follow them.
QuadraticTetMesh promote_to_quadratic(const TetMesh& linear);

} // namespace ligsim::sim
