#include "sim/mesh/quadratic_tet.hpp"

#include "common/error.hpp"
#include "sim/mesh/element_nodes.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace ligsim::sim {

namespace {

/// Every distinct permutation of the barycentric point (a, b, c, d), each with `weight`.
void add_permutations(QuadratureRule& rule, Eigen::Vector4d point, double weight)
{
  std::sort(point.data(), point.data() + 4);
  do {
    rule.points.push_back(point);
    rule.weights.push_back(weight);
  } while (std::next_permutation(point.data(), point.data() + 4));
}

/// dX/d(l1, l2, l3) of an element with rest nodes X at the point whose derivatives are dN.
Eigen::Matrix3d reference_jacobian(const QuadraticTetRows& X, const QuadraticTetRows& dN)
{
  return X.transpose() * dN;
}

Eigen::Vector4d corner(int i)
{
  Eigen::Vector4d l = Eigen::Vector4d::Zero();
  l(i) = 1.0;
  return l;
}

} // namespace

QuadratureRule tet_quadrature(int degree)
{
  QuadratureRule rule;
  rule.degree = degree;
  if (degree == 1) {
    add_permutations(rule, Eigen::Vector4d::Constant(0.25), 1.0);
  } else if (degree == 2) {
    const double b = (5.0 - std::sqrt(5.0)) / 20.0;
    add_permutations(rule, Eigen::Vector4d(1.0 - 3.0 * b, b, b, b), 0.25);
  } else if (degree == 5) {
    // Keast (Comput Methods Appl Mech Eng 1986;55:339), the 15-point rule of degree 5.
    add_permutations(rule, Eigen::Vector4d::Constant(0.25), 0.1817020685825351);
    add_permutations(rule, Eigen::Vector4d(0.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0),
                     0.0361607142857143);
    add_permutations(rule, Eigen::Vector4d(8.0 / 11.0, 1.0 / 11.0, 1.0 / 11.0, 1.0 / 11.0),
                     0.0698714945161738);
    const double a = 0.0665501535736643;
    add_permutations(rule, Eigen::Vector4d(a, a, 0.5 - a, 0.5 - a), 0.0656948493683187);
  } else {
    fail("no tetrahedral quadrature rule of degree {}; there are rules of degree 1, 2 and 5",
         degree);
  }
  return rule;
}

Eigen::Matrix<double, 10, 1> quadratic_shape_functions(const Eigen::Vector4d& l)
{
  Eigen::Matrix<double, 10, 1> N;
  for (int i = 0; i < 4; ++i)
    N(i) = l(i) * (2.0 * l(i) - 1.0);
  for (int k = 0; k < 6; ++k)
    N(4 + k) = 4.0 * l(kQuadraticTetEdges[k][0]) * l(kQuadraticTetEdges[k][1]);
  return N;
}

QuadraticTetRows quadratic_shape_derivatives(const Eigen::Vector4d& l)
{
  // dN/dl_m for the four barycentric coordinates, then d/dl_k = d/dl_k - d/dl_0 (k = 1..3)
  // since l0 = 1 - l1 - l2 - l3.
  Eigen::Matrix<double, 10, 4> by_l = Eigen::Matrix<double, 10, 4>::Zero();
  for (int i = 0; i < 4; ++i)
    by_l(i, i) = 4.0 * l(i) - 1.0;
  for (int k = 0; k < 6; ++k) {
    const auto [i, j] = kQuadraticTetEdges[k];
    by_l(4 + k, i) = 4.0 * l(j);
    by_l(4 + k, j) = 4.0 * l(i);
  }
  QuadraticTetRows dN;
  for (int k = 0; k < 3; ++k)
    dN.col(k) = by_l.col(k + 1) - by_l.col(0);
  return dN;
}

QuadraticTetShape quadratic_tet_shape(const QuadraticTetRows& X, const QuadratureRule& rule)
{
  QuadraticTetShape shape;
  shape.points.resize(rule.points.size());
  for (std::size_t q = 0; q < rule.points.size(); ++q) {
    const QuadraticTetRows dN = quadratic_shape_derivatives(rule.points[q]);
    const Eigen::Matrix3d J = reference_jacobian(X, dN);
    QuadraturePointShape& point = shape.points[q];
    point.det_j = J.determinant();
    // G_i = J^-T dN_i: the chain rule from (l1, l2, l3) to the rest coordinates.
    point.G = dN * J.inverse();
    point.weight = rule.weights[q] * point.det_j / 6.0;
    shape.V0 += point.weight;
  }
  return shape;
}

double jacobian_ratio(const QuadraticTetRows& X, const QuadratureRule& rule)
{
  const Eigen::Matrix3d edges = (X.middleRows<3>(1).rowwise() - X.row(0)).transpose();
  const double straight = edges.determinant();
  double smallest = INFINITY;
  for (int i = 0; i < 4; ++i)
    smallest = std::min(
        smallest, reference_jacobian(X, quadratic_shape_derivatives(corner(i))).determinant());
  for (const Eigen::Vector4d& l : rule.points)
    smallest =
        std::min(smallest, reference_jacobian(X, quadratic_shape_derivatives(l)).determinant());
  return smallest / straight;
}

std::vector<QuadraticTetShape> compute_rest_shapes(const QuadraticTetMesh& mesh,
                                                   const QuadratureRule& rule)
{
  check_element_nodes(mesh.V, mesh.T);
  std::vector<QuadraticTetShape> shapes(static_cast<std::size_t>(mesh.T.rows()));
  for (Eigen::Index e = 0; e < mesh.T.rows(); ++e) {
    QuadraticTetRows X;
    for (int i = 0; i < 10; ++i)
      X.row(i) = mesh.V.row(mesh.T(e, i));
    const double scale = (X.colwise().maxCoeff() - X.colwise().minCoeff()).maxCoeff();
    const double folded = 1e-12 * scale * scale * scale;
    for (int i = 0; i < 4; ++i) {
      const double det =
          reference_jacobian(X, quadratic_shape_derivatives(corner(i))).determinant();
      if (!(det > folded))
        fail("element {} is folded or inverted at its corner node {} (det dX/dl = {} mm^3): "
             "a mid-edge node lies too far from its edge's middle",
             e, mesh.T(e, i), det);
    }
    QuadraticTetShape shape = quadratic_tet_shape(X, rule);
    for (const QuadraturePointShape& point : shape.points)
      if (!(point.det_j > folded))
        fail("element {} is folded or inverted inside (det dX/dl = {} mm^3 at a quadrature "
             "point): a mid-edge node lies too far from its edge's middle",
             e, point.det_j);
    shapes[static_cast<std::size_t>(e)] = std::move(shape);
  }
  return shapes;
}

void flag_mid_edge_nodes(const QuadraticTetrahedra& T, std::vector<bool>& flags, FlaggedEnds ends)
{
  const std::vector<bool> corners = flags;
  for (Eigen::Index e = 0; e < T.rows(); ++e)
    for (int k = 0; k < 6; ++k) {
      const auto [i, j] = kQuadraticTetEdges[static_cast<std::size_t>(k)];
      const bool first = corners[static_cast<std::size_t>(T(e, i))];
      const bool second = corners[static_cast<std::size_t>(T(e, j))];
      if (ends == FlaggedEnds::both ? first && second : first || second)
        flags[static_cast<std::size_t>(T(e, 4 + k))] = true;
    }
}

QuadraticTetMesh promote_to_quadratic(const TetMesh& linear)
{
  QuadraticTetMesh mesh;
  mesh.T.resize(linear.T.rows(), 10);
  std::map<std::pair<int, int>, int> mid_edge;
  std::vector<Eigen::RowVector3d> added;
  const int linear_count = static_cast<int>(linear.V.rows());
  for (Eigen::Index e = 0; e < linear.T.rows(); ++e) {
    for (int i = 0; i < 4; ++i)
      mesh.T(e, i) = linear.T(e, i);
    for (int k = 0; k < 6; ++k) {
      const int a = linear.T(e, kQuadraticTetEdges[k][0]);
      const int b = linear.T(e, kQuadraticTetEdges[k][1]);
      const auto [where, inserted] = mid_edge.try_emplace(
          {std::min(a, b), std::max(a, b)}, linear_count + static_cast<int>(added.size()));
      if (inserted)
        added.push_back(0.5 * (linear.V.row(a) + linear.V.row(b)));
      mesh.T(e, 4 + k) = where->second;
    }
  }
  mesh.V.resize(linear_count + static_cast<Eigen::Index>(added.size()), 3);
  mesh.V.topRows(linear_count) = linear.V;
  for (std::size_t k = 0; k < added.size(); ++k)
    mesh.V.row(linear_count + static_cast<Eigen::Index>(k)) = added[k];
  return mesh;
}

} // namespace ligsim::sim
