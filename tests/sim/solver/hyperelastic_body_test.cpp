#include "common/error.hpp"
#include "sim/mesh/quadratic_tet.hpp"
#include "sim/mesh/structured_mesh.hpp"
#include "sim/solver/hyperelastic_body.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

using namespace ligsim;
using namespace ligsim::sim;

namespace {

/// A 2 x 2 x 3-hex bar of quadratic tets (rule of degree 2, 4 points) with a fiber per
/// quadrature point that turns along the bar.
HyperelasticBody quadratic_bar()
{
  const QuadraticTetMesh mesh =
      promote_to_quadratic(structured_box_mesh({2, 2, 3}, {2.0, 2.0, 3.0}));
  const QuadratureRule rule = tet_quadrature(2);
  const Eigen::Index rows = mesh.T.rows() * static_cast<Eigen::Index>(rule.points.size());
  FiberField fibers(rows, 3);
  for (Eigen::Index k = 0; k < rows; ++k)
    fibers.row(k) =
        1.02 *
        Eigen::RowVector3d(0.2 * std::sin(0.1 * static_cast<double>(k)), 0.1, 1.0).normalized();
  return HyperelasticBody(mesh, mcl_material(), fibers, rule);
}

/// The bar bent and stretched smoothly, with a small random jitter.
Eigen::VectorXd deformed(const HyperelasticBody& body)
{
  Eigen::VectorXd x = body.rest_positions();
  std::mt19937 random(11);
  std::uniform_real_distribution<double> jitter(-0.005, 0.005);
  for (int n = 0; n < body.node_count(); ++n) {
    const Eigen::Vector3d p = x.segment<3>(3 * n);
    x.segment<3>(3 * n) +=
        Eigen::Vector3d(0.03 * p.z() * p.z() + jitter(random), 0.02 * p.x() + jitter(random),
                        0.05 * p.z() + jitter(random));
  }
  return x;
}

} // namespace

TEST(QuadraticBody, ItsGradientAndStiffnessMatchCentralDifferences)
{
  const HyperelasticBody body = quadratic_bar();
  ASSERT_TRUE(body.quadratic());
  const Eigen::VectorXd x = deformed(body);
  Eigen::VectorXd gradient;
  ASSERT_TRUE(std::isfinite(body.energy_gradient(x, gradient).energy));

  std::mt19937 random(5);
  std::normal_distribution<double> normal;
  const double h = 1e-6;
  for (int trial = 0; trial < 3; ++trial) {
    Eigen::VectorXd d(x.size());
    for (Eigen::Index k = 0; k < d.size(); ++k)
      d(k) = normal(random);
    d.normalize();
    const double slope = (body.energy(x + h * d).energy - body.energy(x - h * d).energy) / (2 * h);
    EXPECT_NEAR(slope, gradient.dot(d), 1e-6 * gradient.norm());

    Eigen::VectorXd up;
    Eigen::VectorXd down;
    body.energy_gradient(x + h * d, up);
    body.energy_gradient(x - h * d, down);
    const Eigen::VectorXd fd = (up - down) / (2 * h);
    const Eigen::VectorXd Kd = body.apply_stiffness(x, d);
    EXPECT_LT((Kd - fd).norm(), 1e-6 * Kd.norm());
  }
}

TEST(QuadraticBody, AnAffineMapGivesTheLinearBodysFigures)
{
  const ligsim::TetMesh linear_mesh = structured_box_mesh({2, 2, 3}, {2.0, 2.0, 3.0});
  FiberField fiber(1, 3);
  fiber << 0.1, 0.2, 1.03;
  const HyperelasticBody linear(linear_mesh, mcl_material(), fiber);
  const HyperelasticBody quadratic(promote_to_quadratic(linear_mesh), mcl_material(), fiber,
                                   tet_quadrature(5));
  EXPECT_NEAR(quadratic.rest_volume(), 12.0, 1e-12);
  Eigen::Matrix3d F;
  F << 1.05, 0.1, 0.0, -0.05, 0.98, 0.02, 0.0, 0.03, 1.04;
  auto mapped = [&](const HyperelasticBody& body) {
    Eigen::VectorXd x = body.rest_positions();
    for (int n = 0; n < body.node_count(); ++n)
      x.segment<3>(3 * n) = F * x.segment<3>(3 * n);
    return x;
  };
  const Eigen::VectorXd xl = mapped(linear);
  const Eigen::VectorXd xq = mapped(quadratic);
  EXPECT_NEAR(quadratic.energy(xq).energy, linear.energy(xl).energy,
              1e-12 * linear.energy(xl).energy);
  EXPECT_NEAR(quadratic.volume(xq), 12.0 * F.determinant(), 1e-12);
  EXPECT_NEAR(quadratic.min_j(xq).first, F.determinant(), 1e-13);
  for (Eigen::Index e : {0, 7, 59}) {
    const ElementMeasures a = linear.measures(xl, e);
    const ElementMeasures b = quadratic.measures(xq, e);
    EXPECT_NEAR(b.J, a.J, 1e-13);
    EXPECT_NEAR(b.energy_density_mpa, a.energy_density_mpa, 1e-12);
    EXPECT_NEAR(b.fiber_stretch, a.fiber_stretch, 1e-13);
    EXPECT_NEAR(b.deviatoric_fiber_stretch, a.deviatoric_fiber_stretch, 1e-13);
  }
  // The corners' tets: the linear mesh over every node.
  EXPECT_EQ(quadratic.mesh().T, linear_mesh.T);
  EXPECT_EQ(quadratic.node_count(), quadratic.mesh().V.rows());
}

TEST(QuadraticBody, AFiberFieldOfTheWrongSizeNamesTheSizesItCouldHave)
{
  const QuadraticTetMesh mesh = promote_to_quadratic(structured_cube_mesh(1, 1.0));
  FiberField fibers(7, 3);
  fibers.setConstant(1.0);
  try {
    HyperelasticBody body(mesh, mcl_material(), fibers, tet_quadrature(2));
    FAIL() << "expected an InputError";
  } catch (const ligsim::InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("one per quadrature point (20)"), std::string::npos) << message;
  }
}
