#include "common/error.hpp"
#include "sim/mesh/quadratic_tet.hpp"
#include "sim/mesh/structured_mesh.hpp"
#include "sim/mesh/tet_shape.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <set>
#include <string>
#include <utility>

using namespace ligsim;
using namespace ligsim::sim;
using ligsim::TetMesh;

namespace {

double factorial(int n)
{
  return n <= 1 ? 1.0 : n * factorial(n - 1);
}

/// The integral of l0^a l1^b l2^c l3^d over the reference tet (volume 1/6):
/// a! b! c! d! / (a + b + c + d + 3)!.
double exact_integral(const std::array<int, 4>& powers)
{
  double numerator = 1.0;
  int sum = 0;
  for (int p : powers) {
    numerator *= factorial(p);
    sum += p;
  }
  return numerator / factorial(sum + 3);
}

double rule_integral(const QuadratureRule& rule, const std::array<int, 4>& powers)
{
  double sum = 0.0;
  for (std::size_t q = 0; q < rule.points.size(); ++q) {
    double value = rule.weights[q];
    for (int k = 0; k < 4; ++k)
      value *= std::pow(rule.points[q](k), powers[static_cast<std::size_t>(k)]);
    sum += value;
  }
  return sum / 6.0;
}

/// The one 10-node tet with these corners (a row each), its mid-edge nodes at their middles.
QuadraticTetMesh one_element(const Eigen::Matrix<double, 4, 3, Eigen::RowMajor>& corners)
{
  TetMesh linear;
  linear.V = corners;
  linear.T.resize(1, 4);
  linear.T << 0, 1, 2, 3;
  return promote_to_quadratic(linear);
}

/// A tet with unequal edges, its mid-edge nodes at the middles of its edges.
QuadraticTetRows straight_element()
{
  Eigen::Matrix<double, 4, 3, Eigen::RowMajor> corners;
  corners << 0.1, 0.0, 0.05, 1.1, 0.1, 0.0, 0.2, 0.9, 0.1, 0.15, 0.2, 1.2;
  const QuadraticTetMesh mesh = one_element(corners);
  return quadratic_tet_nodes(mesh.T, 0, mesh.V.reshaped<Eigen::RowMajor>());
}

Eigen::Vector4d random_barycentric(std::mt19937& random)
{
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Eigen::Vector4d l;
  for (int k = 0; k < 4; ++k)
    l(k) = -std::log(unit(random) + 1e-12);
  return l / l.sum();
}

} // namespace

TEST(TetQuadrature, EachRuleIntegratesEveryMonomialUpToItsDegreeExactly)
{
  for (int degree : {1, 2, 5}) {
    const QuadratureRule rule = tet_quadrature(degree);
    double weight_sum = 0.0;
    for (double w : rule.weights) {
      EXPECT_GT(w, 0.0);
      weight_sum += w;
    }
    EXPECT_NEAR(weight_sum, 1.0, 1e-14);
    int checked = 0;
    for (int a = 0; a <= degree; ++a)
      for (int b = 0; a + b <= degree; ++b)
        for (int c = 0; a + b + c <= degree; ++c)
          for (int d = 0; a + b + c + d <= degree; ++d) {
            const std::array<int, 4> powers = {a, b, c, d};
            const double exact = exact_integral(powers);
            EXPECT_NEAR(rule_integral(rule, powers), exact, 1e-14 * 6.0 * exact + 1e-17)
                << "degree " << degree << ", l^(" << a << b << c << d << ")";
            ++checked;
          }
    EXPECT_GT(checked, degree);
  }
  EXPECT_EQ(tet_quadrature(2).points.size(), 4u);
  EXPECT_EQ(tet_quadrature(5).points.size(), 15u);
}

TEST(TetQuadrature, AnUnknownDegreeIsAClearError)
{
  try {
    (void)tet_quadrature(3);
    FAIL() << "expected an InputError";
  } catch (const ligsim::InputError& error) {
    EXPECT_NE(std::string(error.what()).find("degree 3"), std::string::npos) << error.what();
  }
}

TEST(QuadraticShapeFunctions, AreOneAtTheirNodeZeroAtTheOthersAndSumToOne)
{
  std::array<Eigen::Vector4d, 10> nodes;
  for (int i = 0; i < 4; ++i)
    nodes[static_cast<std::size_t>(i)] = Eigen::Vector4d::Unit(i);
  for (int k = 0; k < 6; ++k)
    nodes[static_cast<std::size_t>(4 + k)] =
        0.5 * (Eigen::Vector4d::Unit(kQuadraticTetEdges[k][0]) +
               Eigen::Vector4d::Unit(kQuadraticTetEdges[k][1]));
  for (int j = 0; j < 10; ++j) {
    const auto N = quadratic_shape_functions(nodes[static_cast<std::size_t>(j)]);
    for (int i = 0; i < 10; ++i)
      EXPECT_NEAR(N(i), i == j ? 1.0 : 0.0, 1e-15) << "N_" << i << " at node " << j;
  }
  std::mt19937 random(3);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Vector4d l = random_barycentric(random);
    EXPECT_NEAR(quadratic_shape_functions(l).sum(), 1.0, 1e-14);
    EXPECT_LT(quadratic_shape_derivatives(l).colwise().sum().norm(), 1e-13);
  }
}

TEST(QuadraticShapeFunctions, DerivativesMatchCentralDifferences)
{
  std::mt19937 random(5);
  const double h = 1e-6;
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::Vector4d l = random_barycentric(random);
    const QuadraticTetRows dN = quadratic_shape_derivatives(l);
    for (int k = 0; k < 3; ++k) {
      // Moving l_(k+1) moves l0 the other way.
      Eigen::Vector4d step = Eigen::Vector4d::Zero();
      step(k + 1) = h;
      step(0) = -h;
      const Eigen::Matrix<double, 10, 1> fd =
          (quadratic_shape_functions(l + step) - quadratic_shape_functions(l - step)) / (2 * h);
      EXPECT_LT((fd - dN.col(k)).norm(), 1e-8) << "d/dl" << k + 1;
    }
  }
}

TEST(QuadraticTetShape, AStraightElementHasTheLinearVolumeAndReproducesAnAffineMap)
{
  const QuadraticTetRows X = straight_element();
  TetCorners corners = X.topRows<4>();
  const double linear_volume = tet_shape(corners).V0;
  Eigen::Matrix3d A;
  A << 1.1, 0.2, -0.1, 0.05, 0.9, 0.3, -0.2, 0.1, 1.2;
  const QuadraticTetRows Q = (X * A.transpose()).rowwise() + Eigen::RowVector3d(1, 2, 3);
  for (int degree : {1, 2, 5}) {
    const QuadraticTetShape shape = quadratic_tet_shape(X, tet_quadrature(degree));
    EXPECT_NEAR(shape.V0, linear_volume, 1e-14);
    for (const QuadraturePointShape& point : shape.points)
      EXPECT_LT((Q.transpose() * point.G - A).norm(), 1e-13) << "degree " << degree;
  }
}

TEST(QuadraticTetShape, ACurvedElementsVolumeIsExactWithTheRulesOfDegreeTwoAndUp)
{
  // Two mid-edge nodes moved apart from their edges make dX/dl a straight element's Jacobian
  // plus two rank-one terms linear in l, so det dX/dl is a polynomial of degree 2: the rules
  // of degree 2 and 5 integrate it exactly, and the centroid rule does not.
  QuadraticTetRows X = straight_element();
  X.row(4) += Eigen::RowVector3d(0.0, -0.15, 0.1);
  X.row(5) += Eigen::RowVector3d(0.12, 0.05, 0.0);
  const double two = quadratic_tet_shape(X, tet_quadrature(2)).V0;
  const double five = quadratic_tet_shape(X, tet_quadrature(5)).V0;
  const double one = quadratic_tet_shape(X, tet_quadrature(1)).V0;
  EXPECT_NEAR(two, five, 1e-14);
  EXPECT_GT(std::abs(one - five), 1e-4);
}

TEST(QuadraticTetShape, AFoldedElementIsRejectedByName)
{
  TetMesh linear = structured_cube_mesh(1, 1.0);
  QuadraticTetMesh mesh = promote_to_quadratic(linear);
  EXPECT_NO_THROW((void)compute_rest_shapes(mesh, tet_quadrature(2)));
  // Drag the mid-edge node of element 0's edge (0, 1) past corner 1.
  const int mid = mesh.T(0, 4);
  const Eigen::RowVector3d corner1 = mesh.V.row(mesh.T(0, 1));
  mesh.V.row(mid) = corner1 + 0.8 * (corner1 - mesh.V.row(mesh.T(0, 0)));
  try {
    (void)compute_rest_shapes(mesh, tet_quadrature(2));
    FAIL() << "expected an InputError";
  } catch (const ligsim::InputError& error) {
    EXPECT_NE(std::string(error.what()).find("folded"), std::string::npos) << error.what();
  }
  mesh = promote_to_quadratic(linear);
  mesh.T(2, 7) = static_cast<int>(mesh.V.rows());
  EXPECT_THROW((void)compute_rest_shapes(mesh, tet_quadrature(2)), ligsim::InputError);
}

TEST(PromoteToQuadratic, AddsOneSharedNodeAtTheMiddleOfEveryEdge)
{
  const TetMesh linear = structured_box_mesh({3, 2, 2}, {3.0, 2.0, 2.5});
  std::set<std::pair<int, int>> edges;
  for (Eigen::Index e = 0; e < linear.T.rows(); ++e)
    for (const auto& [i, j] : kQuadraticTetEdges) {
      const int a = linear.T(e, i);
      const int b = linear.T(e, j);
      edges.insert({std::min(a, b), std::max(a, b)});
    }
  const QuadraticTetMesh mesh = promote_to_quadratic(linear);
  ASSERT_EQ(mesh.V.rows(), linear.V.rows() + static_cast<Eigen::Index>(edges.size()));
  EXPECT_EQ(mesh.V.topRows(linear.V.rows()), linear.V);
  std::set<int> mid_nodes;
  for (Eigen::Index e = 0; e < mesh.T.rows(); ++e) {
    EXPECT_EQ(mesh.T.row(e).head<4>(), linear.T.row(e));
    for (int k = 0; k < 6; ++k) {
      const int mid = mesh.T(e, 4 + k);
      mid_nodes.insert(mid);
      const Eigen::RowVector3d middle = 0.5 * (mesh.V.row(mesh.T(e, kQuadraticTetEdges[k][0])) +
                                               mesh.V.row(mesh.T(e, kQuadraticTetEdges[k][1])));
      EXPECT_LT((mesh.V.row(mid) - middle).norm(), 1e-15);
    }
  }
  EXPECT_EQ(mid_nodes.size(), edges.size());
}

TEST(FlagMidEdgeNodes, FlagsAnEdgesMiddleWhereBothOrEitherOfItsEndsAre)
{
  Eigen::Matrix<double, 4, 3, Eigen::RowMajor> corners;
  corners << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  const QuadraticTetMesh mesh = one_element(corners);
  // Corners 0 and 1 flagged: edge 0-1 has both ends; edges 0-2, 0-3, 1-2, 1-3 one; 2-3 none.
  std::vector<bool> start(static_cast<std::size_t>(mesh.V.rows()), false);
  start[0] = start[1] = true;
  std::vector<bool> both = start;
  flag_mid_edge_nodes(mesh.T, both, FlaggedEnds::both);
  std::vector<bool> either = start;
  flag_mid_edge_nodes(mesh.T, either, FlaggedEnds::either);
  for (int k = 0; k < 6; ++k) {
    const auto [i, j] = kQuadraticTetEdges[static_cast<std::size_t>(k)];
    const auto mid = static_cast<std::size_t>(mesh.T(0, 4 + k));
    EXPECT_EQ(both[mid], start[i] && start[j]) << "edge " << i << "-" << j;
    EXPECT_EQ(either[mid], start[i] || start[j]) << "edge " << i << "-" << j;
  }
  for (std::size_t n = 0; n < 4; ++n)
    EXPECT_EQ(both[n], start[n]);
}
