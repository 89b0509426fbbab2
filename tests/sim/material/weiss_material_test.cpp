#include "sim/material/weiss_material.hpp"

#include "common/error.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/QR>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <tuple>

using namespace ligsim::sim;

namespace {

TetCorners rest_corners()
{
  TetCorners P;
  P << 0.1, 0.0, 0.05, 1.1, 0.1, 0.0, 0.2, 0.9, 0.1, 0.15, 0.2, 1.2;
  return P;
}

/// A deformation that stretches the unit fiber `a` to deviatoric stretch `lambda` and changes
/// the volume by `J`, with a small random shear and a rotation on top.
TetCorners deformed(const TetCorners& P, const Eigen::Vector3d& a, double lambda, double J,
                    unsigned seed)
{
  const Eigen::Matrix3d along = a * a.transpose();
  const Eigen::Matrix3d stretch =
      std::cbrt(J) * (lambda * along + (Eigen::Matrix3d::Identity() - along) / std::sqrt(lambda));
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> small(-1e-3, 1e-3);
  Eigen::Matrix3d shear = Eigen::Matrix3d::Identity();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      shear(i, j) += small(random);
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Matrix3d F = rotation * stretch * shear;
  TetCorners Q;
  for (int i = 0; i < 4; ++i)
    Q.row(i) = (F * P.row(i).transpose()).transpose() + Eigen::RowVector3d(0.3, -0.2, 0.1);
  return Q;
}

MaterialParameters material(FiberConvention convention, VolumetricLaw volumetric)
{
  MaterialParameters parameters = mcl_material();
  parameters.fiber->convention = convention;
  parameters.volumetric = volumetric;
  return parameters;
}

Vector12d gradient_at(const WeissMaterial& m, const TetCorners& Q, const TetShape& shape,
                      const Eigen::Vector3d& a)
{
  ElementEvaluation e;
  m.evaluate(Q, shape, a, ElementNeeds::gradient, e);
  return e.gradient;
}

double energy_at(const WeissMaterial& m, const TetCorners& Q, const TetShape& shape,
                 const Eigen::Vector3d& a)
{
  ElementEvaluation e;
  m.evaluate(Q, shape, a, ElementNeeds::energy, e);
  return e.energy;
}

/// (regime stretch, fiber convention, volumetric law)
using Case = std::tuple<double, FiberConvention, VolumetricLaw>;

class ElementDerivatives : public ::testing::TestWithParam<Case> {};

} // namespace

TEST(TetShape, ShapeVectorsAreBarycentricGradients)
{
  const TetCorners P = rest_corners();
  const TetShape shape = tet_shape(P);
  EXPECT_GT(shape.V0, 0.0);
  EXPECT_LT((shape.D.colwise().sum()).norm(), 1e-14);
  const Eigen::Matrix3d identity = P.transpose() * shape.D;
  EXPECT_LT((identity - Eigen::Matrix3d::Identity()).norm(), 1e-14);
}

TEST_P(ElementDerivatives, ForcesAndStiffnessMatchCentralDifferences)
{
  const auto [lambda, convention, volumetric] = GetParam();
  const WeissMaterial m(material(convention, volumetric));
  const TetCorners P = rest_corners();
  const TetShape shape = tet_shape(P);
  const Eigen::Vector3d a = Eigen::Vector3d(0.3, 0.2, 1.0).normalized();
  const TetCorners Q = deformed(P, a, lambda, 1.01, 7);

  ElementEvaluation at;
  m.evaluate(Q, shape, a, ElementNeeds::hessian, at);
  ASSERT_FALSE(at.inverted);
  const ElementMeasures measures = m.measures(Q, shape, a);
  const FiberRegime regime = m.fiber_law()->regime(measures.deviatoric_fiber_stretch);
  const FiberRegime expected = m.fiber_law()->regime(lambda);
  ASSERT_EQ(regime, expected) << "the test deformation left its regime";

  const double h = 1e-6;
  Vector12d gradient_fd;
  Matrix12d hessian_fd;
  for (int k = 0; k < 12; ++k) {
    TetCorners plus = Q;
    TetCorners minus = Q;
    plus(k / 3, k % 3) += h;
    minus(k / 3, k % 3) -= h;
    gradient_fd(k) = (energy_at(m, plus, shape, a) - energy_at(m, minus, shape, a)) / (2 * h);
    hessian_fd.col(k) =
        (gradient_at(m, plus, shape, a) - gradient_at(m, minus, shape, a)) / (2 * h);
  }
  const double gradient_error = (gradient_fd - at.gradient).norm() / at.gradient.norm();
  const double hessian_error = (hessian_fd - at.hessian).norm() / at.hessian.norm();
  EXPECT_LT(gradient_error, 1e-6);
  EXPECT_LT(hessian_error, 1e-6);
  EXPECT_LT((at.hessian - at.hessian.transpose()).norm(), 1e-10 * at.hessian.norm());
}

INSTANTIATE_TEST_SUITE_P(
    RegimesConventionsVolumetric, ElementDerivatives,
    ::testing::Combine(::testing::Values(0.97, 1.015, 1.08),
                       ::testing::Values(FiberConvention::paper, FiberConvention::weiss),
                       ::testing::Values(VolumetricLaw::jm1, VolumetricLaw::lnj)),
    [](const ::testing::TestParamInfo<Case>& info) {
      const double lambda = std::get<0>(info.param);
      const std::string regime = lambda < 1 ? "slack" : lambda < 1.03 ? "toe" : "linear";
      return regime + "_" + to_string(std::get<1>(info.param)) + "_" +
             to_string(std::get<2>(info.param));
    });

TEST(WeissMaterial, NeoHookeanWithoutFibersMatchesCentralDifferences)
{
  MaterialParameters parameters;
  const WeissMaterial m(parameters);
  ASSERT_FALSE(m.has_fibers());
  const TetCorners P = rest_corners();
  const TetShape shape = tet_shape(P);
  const Eigen::Vector3d unused = Eigen::Vector3d::Zero();
  const TetCorners Q = deformed(P, Eigen::Vector3d::UnitX(), 1.2, 0.97, 3);
  ElementEvaluation at;
  m.evaluate(Q, shape, unused, ElementNeeds::hessian, at);
  const double h = 1e-6;
  Matrix12d hessian_fd;
  for (int k = 0; k < 12; ++k) {
    TetCorners plus = Q;
    TetCorners minus = Q;
    plus(k / 3, k % 3) += h;
    minus(k / 3, k % 3) -= h;
    hessian_fd.col(k) =
        (gradient_at(m, plus, shape, unused) - gradient_at(m, minus, shape, unused)) / (2 * h);
  }
  EXPECT_LT((hessian_fd - at.hessian).norm() / at.hessian.norm(), 1e-6);
}

TEST(WeissMaterial, RestStateIsStressFreeAndRigidMotionsCostNothing)
{
  const WeissMaterial m(mcl_material());
  const TetCorners P = rest_corners();
  const TetShape shape = tet_shape(P);
  const Eigen::Vector3d a = Eigen::Vector3d(0, 0, 1);
  ElementEvaluation rest;
  m.evaluate(P, shape, a, ElementNeeds::gradient, rest);
  EXPECT_NEAR(rest.energy, 0.0, 1e-14);
  EXPECT_LT(rest.gradient.norm(), 1e-12);
  const TetCorners moved = deformed(P, a, 1.0, 1.0, 0); // rotation + tiny shear only
  ElementEvaluation rigid;
  m.evaluate(moved, shape, a, ElementNeeds::energy, rigid);
  EXPECT_LT(rigid.energy, 1e-3 * 27.7 * shape.V0); // only the 1e-3 shear costs energy
}

TEST(WeissMaterial, InSituStrainStretchesTheFiberAtRest)
{
  // Sec. 2.7: a' = (1 + c) a puts the fiber under strain c with no deformation.
  const WeissMaterial m(mcl_material());
  const TetCorners P = rest_corners();
  const TetShape shape = tet_shape(P);
  const Eigen::Vector3d a = 1.029 * Eigen::Vector3d(0, 0, 1);
  const ElementMeasures measures = m.measures(P, shape, a);
  EXPECT_NEAR(measures.fiber_stretch, 1.029, 1e-12);
  EXPECT_NEAR(measures.deviatoric_fiber_stretch, 1.029, 1e-12);
  EXPECT_GT(measures.energy_density_mpa, 0.0);
}

TEST(WeissMaterial, InvertedElementHasInfiniteEnergy)
{
  const WeissMaterial m(mcl_material());
  const TetCorners P = rest_corners();
  const TetShape shape = tet_shape(P);
  TetCorners Q = P;
  Q.row(3) = P.row(0) - (P.row(3) - P.row(0)); // mirror node 3 through node 0
  ElementEvaluation e;
  m.evaluate(Q, shape, Eigen::Vector3d::UnitZ(), ElementNeeds::hessian, e);
  EXPECT_TRUE(e.inverted);
  EXPECT_TRUE(std::isinf(e.energy));
}

TEST(WeissMaterial, BadParametersAreRejected)
{
  MaterialParameters parameters = mcl_material();
  parameters.bulk_modulus_mpa = -1.0;
  EXPECT_THROW(WeissMaterial{parameters}, ligsim::InputError);
  parameters = mcl_material();
  parameters.fiber->lambda_star = 0.99;
  EXPECT_THROW(WeissMaterial{parameters}, ligsim::InputError);
}

TEST(PsdProjection, AnElementsHessianProjectsAsItsEigenvaluesSay)
{
  // project_to_psd settles an element whose Hessian is PSD by a Cholesky of one 9x9 block,
  // relying on the Hessian annihilating translations: stretched, compressed and sheared, the
  // result must be the eigen-decomposition's. A stiff bulk makes most states indefinite (their
  // rotation modes feel the pressure); a slightly dilated element is PSD.
  const WeissMaterial m(mcl_material());
  const TetCorners P = rest_corners();
  const TetShape shape = tet_shape(P);
  const Eigen::Vector3d a = Eigen::Vector3d(0.3, 0.2, 1.0).normalized();
  int indefinite = 0, definite = 0;
  for (const double lambda : {0.6, 0.8, 0.95, 1.0, 1.03, 1.08, 1.2})
    for (const double J : {0.9, 1.0, 1.002, 1.005, 1.02, 1.1}) {
      ElementEvaluation at;
      m.evaluate(deformed(P, a, lambda, J, 11), shape, a, ElementNeeds::hessian, at);
      const Eigen::SelfAdjointEigenSolver<Matrix12d> eigen(at.hessian);
      const double size = at.hessian.cwiseAbs().maxCoeff();
      const Matrix12d clamped = eigen.eigenvectors() *
                                eigen.eigenvalues().cwiseMax(0.0).asDiagonal() *
                                eigen.eigenvectors().transpose();
      Matrix12d projected = at.hessian;
      const bool changed = project_to_psd(projected);
      EXPECT_LT((projected - clamped).cwiseAbs().maxCoeff(), 1e-9 * size) << lambda << " " << J;
      const bool negative = eigen.eigenvalues().minCoeff() < -1e-9 * size;
      // Indefinite: projected; PSD (its translation and rotation modes zero to round-off): left
      // as it is, where the eigenvalues' round-off alone would count it as projected.
      EXPECT_EQ(changed, negative) << lambda << " " << J;
      (negative ? indefinite : definite) += 1;
    }
  EXPECT_GT(indefinite, 0); // both kinds were met
  EXPECT_GT(definite, 0);
}

TEST(PsdProjection, ClampsNegativeEigenvaluesOnly)
{
  Matrix12d H = Matrix12d::Identity();
  H(0, 0) = -2.0;
  EXPECT_TRUE(project_to_psd(H));
  EXPECT_NEAR(H(0, 0), 0.0, 1e-14);
  EXPECT_NEAR(H(5, 5), 1.0, 1e-14);
  Matrix12d positive = Matrix12d::Identity();
  EXPECT_FALSE(project_to_psd(positive));
}

TEST(PsdProjection, MirrorsATenNodeTetsNegativeEigenvalues)
{
  // A rotated diagonal: eigenvalues -2 and -0.5 become 2 and 0.5, the rest stay.
  using Matrix30d = Eigen::Matrix<double, 30, 30>;
  Eigen::Matrix<double, 30, 1> values = Eigen::Matrix<double, 30, 1>::LinSpaced(30, 1.0, 30.0);
  values(3) = -2.0;
  values(17) = -0.5;
  const Matrix30d Q = Eigen::HouseholderQR<Matrix30d>(Matrix30d::Random()).householderQ();
  Matrix30d H = Q * values.asDiagonal() * Q.transpose();
  EXPECT_TRUE(project_to_psd(H));
  Eigen::Matrix<double, 30, 1> expected = values.cwiseAbs();
  std::sort(expected.data(), expected.data() + 30);
  const Eigen::Matrix<double, 30, 1> got =
      Eigen::SelfAdjointEigenSolver<Matrix30d>(H).eigenvalues();
  EXPECT_LT((got - expected).cwiseAbs().maxCoeff(), 1e-12);
}
