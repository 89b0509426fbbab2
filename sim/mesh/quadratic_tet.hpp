#pragma once
/// @brief 10-node (quadratic) tetrahedra: meshes, shape functions, quadrature rules and the rest
/// shape at each quadrature point.

#include "common/mesh.hpp"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace ligsim::sim {

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

/// The rule the knee's 10-node tets are integrated with: degree 2, 4 points, FEBio's TET10G4.
/// The Weiss material is not polynomial, so no rule is exact: on a cube of 3^3 hexes of them the
/// top reaction moves 0.03 % from degree 2 to 5, against 2 % from that mesh to the next finer.
inline constexpr int kQuadraticTetRuleDegree = 2;

/// The cell array of fibers.vtu and model.vtu of 10-node tets: a fiber at each point of the rule
/// of kQuadraticTetRuleDegree, 3 columns per point.
inline constexpr const char* kFibersAtPoints = "fiber_at_points";

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

/// The smallest det dX/dl over the corners and the points of `rule` of an element with rest
/// nodes `X`, over that of the straight element on its corners (6 times its volume): 1 for a
/// straight element, 0 or less where a mid-edge node folds it.
double jacobian_ratio(const QuadraticTetRows& X, const QuadratureRule& rule);

/// Checks `mesh` (finite coordinates, node indices in range, det dX/dl positive at every
/// quadrature point and at every corner) and returns every element's rest shape. Throws
/// InputError naming the first offending node or element and the cause.
std::vector<QuadraticTetShape> compute_rest_shapes(const QuadraticTetMesh& mesh,
                                                   const QuadratureRule& rule);

/// The linear mesh with a node added at the middle of every edge (shared by the elements around
/// it). The linear nodes keep their indices; the mid-edge nodes follow them.
QuadraticTetMesh promote_to_quadratic(const TetMesh& linear);

/// Which of an edge's ends must be flagged for its middle to be.
enum class FlaggedEnds { both, either };

/// Sets the flag (one per node of `T`'s mesh) of each mid-edge node whose edge has `ends`
/// flagged: bound to a bone where both ends are (the edge then lies in the footprint); left out
/// of the penetration check where either is (the edge may enter the bone with its bound end).
void flag_mid_edge_nodes(const QuadraticTetrahedra& T, std::vector<bool>& flags,
                         FlaggedEnds ends = FlaggedEnds::both);

} // namespace ligsim::sim
