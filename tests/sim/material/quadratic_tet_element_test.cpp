#include "sim/material/quadratic_tet_element.hpp"
#include "sim/mesh/structured_mesh.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <tuple>
#include <vector>

using namespace ligsim;
using namespace ligsim::sim;

namespace {

using Vector30d = Eigen::Matrix<double, 30, 1>;
using Matrix30d = Eigen::Matrix<double, 30, 30>;

/// A tet with unequal edges, two mid-edge nodes off their edges' middles.
QuadraticTetRows curved_rest_nodes()
{
  TetCorners corners;
  corners << 0.1, 0.0, 0.05, 1.1, 0.1, 0.0, 0.2, 0.9, 0.1, 0.15, 0.2, 1.2;
  QuadraticTetRows X;
  X.topRows<4>() = corners;
  for (int k = 0; k < 6; ++k)
    X.row(4 + k) =
        0.5 * (corners.row(kQuadraticTetEdges[k][0]) + corners.row(kQuadraticTetEdges[k][1]));
  X.row(4) += Eigen::RowVector3d(0.0, -0.08, 0.05);
  X.row(9) += Eigen::RowVector3d(0.06, 0.03, 0.0);
  return X;
}

/// Stretches the unit fiber `a` to deviatoric stretch `lambda` at volume ratio `J`, rotated.
Eigen::Matrix3d fiber_stretch(const Eigen::Vector3d& a, double lambda, double J)
{
  const Eigen::Matrix3d along = a * a.transpose();
  const Eigen::Matrix3d stretch =
      std::cbrt(J) * (lambda * along + (Eigen::Matrix3d::Identity() - along) / std::sqrt(lambda));
  return Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix() * stretch;
}

QuadraticTetRows mapped(const QuadraticTetRows& X, const Eigen::Matrix3d& F)
{
  return (X * F.transpose()).rowwise() + Eigen::RowVector3d(0.3, -0.2, 0.1);
}

QuadraticTetEvaluation evaluated(const WeissMaterial& m, const QuadraticTetRows& Q,
                                 const QuadraticTetShape& shape,
                                 const std::vector<Eigen::Vector3d>& fibers, ElementNeeds needs)
{
  QuadraticTetEvaluation out;
  evaluate_quadratic_tet(m, Q, shape, fibers.data(), fibers.size(), needs, out);
  return out;
}

/// (quadrature degree, fiber stretch)
using Case = std::tuple<int, double>;

class QuadraticTetDerivatives : public ::testing::TestWithParam<Case> {};

} // namespace

TEST_P(QuadraticTetDerivatives, ForcesAndStiffnessMatchCentralDifferences)
{
  const auto [degree, lambda] = GetParam();
  const WeissMaterial m(mcl_material());
  const QuadraticTetRows X = curved_rest_nodes();
  const QuadraticTetShape shape = quadratic_tet_shape(X, tet_quadrature(degree));
  // A fiber field that turns across the element, one vector per quadrature point.
  std::vector<Eigen::Vector3d> fibers;
  for (std::size_t q = 0; q < shape.points.size(); ++q)
    fibers.push_back(Eigen::Vector3d(0.3 + 0.05 * static_cast<double>(q), 0.2, 1.0).normalized());
  // A non-affine deformation: the fiber stretch, plus random mid-edge and corner offsets.
  QuadraticTetRows Q = mapped(X, fiber_stretch(fibers[0], lambda, 1.01));
  std::mt19937 random(7);
  std::uniform_real_distribution<double> small(-0.01, 0.01);
  for (int i = 0; i < 10; ++i)
    for (int a = 0; a < 3; ++a)
      Q(i, a) += small(random);

  const QuadraticTetEvaluation at = evaluated(m, Q, shape, fibers, ElementNeeds::hessian);
  ASSERT_FALSE(at.inverted);
  const double h = 1e-6;
  Vector30d gradient_fd;
  Matrix30d hessian_fd;
  for (int k = 0; k < 30; ++k) {
    QuadraticTetRows plus = Q;
    QuadraticTetRows minus = Q;
    plus(k / 3, k % 3) += h;
    minus(k / 3, k % 3) -= h;
    const QuadraticTetEvaluation up = evaluated(m, plus, shape, fibers, ElementNeeds::gradient);
    const QuadraticTetEvaluation down = evaluated(m, minus, shape, fibers, ElementNeeds::gradient);
    gradient_fd(k) = (up.energy - down.energy) / (2 * h);
    hessian_fd.col(k) = (up.gradient - down.gradient) / (2 * h);
  }
  EXPECT_LT((gradient_fd - at.gradient).norm() / at.gradient.norm(), 1e-6);
  EXPECT_LT((hessian_fd - at.hessian).norm() / at.hessian.norm(), 1e-6);
  EXPECT_LT((at.hessian - at.hessian.transpose()).norm(), 1e-10 * at.hessian.norm());
}

INSTANTIATE_TEST_SUITE_P(RulesAndRegimes, QuadraticTetDerivatives,
                         ::testing::Combine(::testing::Values(2, 5),
                                            ::testing::Values(0.97, 1.015, 1.08)),
                         [](const ::testing::TestParamInfo<Case>& info) {
                           const double lambda = std::get<1>(info.param);
                           const std::string regime = lambda < 1      ? "slack"
                                                      : lambda < 1.03 ? "toe"
                                                                      : "linear";
                           return "degree" + std::to_string(std::get<0>(info.param)) + "_" + regime;
                         });

TEST(QuadraticTetElement, AStraightElementStretchedUniformlyIsTheLinearTet)
{
  // Under a uniform F the energy is V0 W(F), as for the linear tet; the forces go to the
  // mid-edge nodes alone (the integral of grad N is zero for a corner's N), each the sum of the
  // linear tet's forces at its edge's two corners.
  const WeissMaterial m(mcl_material());
  TetCorners corners = curved_rest_nodes().topRows<4>();
  QuadraticTetRows X;
  X.topRows<4>() = corners;
  for (int k = 0; k < 6; ++k)
    X.row(4 + k) =
        0.5 * (corners.row(kQuadraticTetEdges[k][0]) + corners.row(kQuadraticTetEdges[k][1]));
  const Eigen::Vector3d a = Eigen::Vector3d(0.3, 0.2, 1.0).normalized();
  const Eigen::Matrix3d F = fiber_stretch(a, 1.06, 0.99);
  ElementEvaluation linear;
  m.evaluate(mapped(X, F).topRows<4>(), tet_shape(corners), a, ElementNeeds::gradient, linear);
  for (int degree : {1, 2, 5}) {
    const QuadraticTetShape shape = quadratic_tet_shape(X, tet_quadrature(degree));
    const QuadraticTetEvaluation quadratic =
        evaluated(m, mapped(X, F), shape, {a}, ElementNeeds::gradient);
    EXPECT_NEAR(quadratic.energy, linear.energy, 1e-12 * linear.energy) << "degree " << degree;
    const double scale = linear.gradient.norm();
    for (int i = 0; i < 4; ++i)
      EXPECT_LT(quadratic.gradient.segment<3>(3 * i).norm(), 1e-12 * scale) << "corner " << i;
    for (int k = 0; k < 6; ++k) {
      const Eigen::Vector3d expected = linear.gradient.segment<3>(3 * kQuadraticTetEdges[k][0]) +
                                       linear.gradient.segment<3>(3 * kQuadraticTetEdges[k][1]);
      EXPECT_LT((quadratic.gradient.segment<3>(3 * (4 + k)) - expected).norm(), 1e-12 * scale)
          << "mid-edge node " << 4 + k << ", degree " << degree;
    }
  }
}

TEST(QuadraticTetElement, PatchTestAnAffineFieldLeavesEveryInteriorNodeInEquilibrium)
{
  const WeissMaterial m(mcl_material());
  const Eigen::Vector3d size(3.0, 2.0, 2.5);
  const QuadraticTetMesh mesh = promote_to_quadratic(structured_box_mesh({3, 3, 3}, size));
  const QuadratureRule rule = tet_quadrature(2);
  const std::vector<QuadraticTetShape> shapes = compute_rest_shapes(mesh, rule);
  const Eigen::Vector3d a = Eigen::Vector3d(0.3, 0.2, 1.0).normalized();
  const Eigen::Matrix3d F = fiber_stretch(a, 1.05, 1.02);
  Eigen::VectorXd x(3 * mesh.V.rows());
  for (Eigen::Index n = 0; n < mesh.V.rows(); ++n)
    x.segment<3>(3 * n) = F * mesh.V.row(n).transpose();

  Eigen::VectorXd gradient = Eigen::VectorXd::Zero(x.size());
  double energy = 0.0;
  double volume = 0.0;
  for (Eigen::Index e = 0; e < mesh.T.rows(); ++e) {
    const QuadraticTetShape& shape = shapes[static_cast<std::size_t>(e)];
    const QuadraticTetEvaluation element =
        evaluated(m, quadratic_tet_nodes(mesh.T, e, x), shape, {a}, ElementNeeds::gradient);
    energy += element.energy;
    volume += shape.V0;
    for (int i = 0; i < 10; ++i)
      gradient.segment<3>(3 * mesh.T(e, i)) += element.gradient.segment<3>(3 * i);
  }
  EXPECT_NEAR(volume, size.prod(), 1e-12);
  // The energy of the uniform state, from one linear tet of unit volume.
  TetCorners unit;
  unit << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  TetCorners unit_deformed = unit * F.transpose();
  ElementEvaluation reference;
  m.evaluate(unit_deformed, tet_shape(unit), a, ElementNeeds::energy, reference);
  EXPECT_NEAR(energy, reference.energy / tet_shape(unit).V0 * size.prod(), 1e-11 * energy);

  int interior = 0;
  const double largest = gradient.cwiseAbs().maxCoeff();
  for (Eigen::Index n = 0; n < mesh.V.rows(); ++n) {
    const Eigen::RowVector3d p = mesh.V.row(n);
    const bool inside =
        (p.array() > 1e-9).all() && (p.transpose().array() < size.array() - 1e-9).all();
    if (!inside)
      continue;
    ++interior;
    EXPECT_LT(gradient.segment<3>(3 * n).norm(), 1e-11 * largest) << "interior node " << n;
  }
  EXPECT_GT(interior, 20);
}

TEST(QuadraticTetElement, AnElementFoldedAtOnePointIsInverted)
{
  const WeissMaterial m(mcl_material());
  const QuadraticTetRows X = curved_rest_nodes();
  const QuadraticTetShape shape = quadratic_tet_shape(X, tet_quadrature(5));
  QuadraticTetRows Q = X;
  Q.row(4) = X.row(1) + 0.9 * (X.row(1) - X.row(0)); // mid-edge node dragged past corner 1
  const QuadraticTetEvaluation folded =
      evaluated(m, Q, shape, {Eigen::Vector3d::UnitZ()}, ElementNeeds::hessian);
  EXPECT_TRUE(folded.inverted);
  EXPECT_TRUE(std::isinf(folded.energy));
  EXPECT_LE(folded.J, 0.0);
}
