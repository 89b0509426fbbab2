/// The stiffness a body shows at its prescribed DOFs once its free ones re-equilibrate: the
/// Schur complement along two motions of a cube's top face (a stretch and a shear), against
/// central differences of the reactions of equilibria solved with the top moved; and the free
/// nodes' response to the motions, against the differences of those equilibria.

#include "sim/mesh/node_selection.hpp"
#include "sim/mesh/structured_mesh.hpp"
#include "sim/solver/condensed_stiffness.hpp"
#include "sim/solver/static_solver.hpp"
#include "tests/sim/solver/indefinite_until_projected.hpp"

#include <gtest/gtest.h>

using namespace ligsim::sim;

namespace {

struct TopMoved {
  BoundaryConditions conditions;
  std::vector<int> top;
};

/// Bottom fixed, top moved by `move` (mm) at load factor 1.
TopMoved cube_with_top(const ligsim::TetMesh& mesh, const Eigen::Vector3d& move)
{
  TopMoved c;
  ConstraintSet bottom;
  bottom.name = "bottom";
  bottom.nodes = nodes_on_plane(mesh.V, 2, 0.0, 1e-9);
  ConstraintSet top;
  top.name = "top";
  top.nodes = nodes_on_plane(mesh.V, 2, 1.0, 1e-9);
  top.displacement_mm = move;
  c.top = top.nodes;
  c.conditions.constraints = {bottom, top};
  return c;
}

/// The equilibrium with the top moved by `move`, and its reaction residual.
Eigen::VectorXd reactions(const HyperelasticBody& body, const Eigen::Vector3d& move,
                          Eigen::VectorXd* x_out = nullptr)
{
  const TopMoved c = cube_with_top(body.mesh(), move);
  NewtonSettings settings;
  settings.load_steps = 4;
  settings.residual_tolerance = 1e-12;
  StaticSolver solver(body, c.conditions, settings);
  Eigen::VectorXd x = body.rest_positions(), residual;
  const StaticResult result = solver.solve(x, [&](const StepReport&, const Eigen::VectorXd&,
                                                  const Eigen::VectorXd& r) { residual = r; });
  EXPECT_TRUE(result.converged) << result.failure;
  if (x_out)
    *x_out = x;
  return residual;
}

} // namespace

TEST(CondensedStiffness, ItIsTheDerivativeOfTheReactionsOnceTheBodyReequilibrates)
{
  FiberField fiber(1, 3);
  fiber << 0.3, 0.0, 1.0;
  const HyperelasticBody body(structured_box_mesh({3, 3, 3}, {1.0, 1.0, 1.0}), mcl_material(),
                              fiber);
  // A stretched and sheared state, where the stiffness is not the rest one.
  const Eigen::Vector3d base(0.02, 0.0, 0.06);
  Eigen::VectorXd x;
  reactions(body, base, &x);
  const TopMoved c = cube_with_top(body.mesh(), base);
  // The two motions: the top stretched along z and sheared along x.
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(body.dof_count(), 2);
  for (int n : c.top) {
    D(3 * n + 2, 0) = 1.0;
    D(3 * n + 0, 1) = 1.0;
  }
  const CondensedStiffness S = condensed_stiffness(body, c.conditions, x, nullptr, 1.0, D);
  EXPECT_EQ(S.factor, "exact");
  const double h = 1e-5;
  for (int k = 0; k < 2; ++k) {
    const Eigen::Vector3d step = k == 0 ? Eigen::Vector3d(0, 0, h) : Eigen::Vector3d(h, 0, 0);
    const Eigen::VectorXd plus = reactions(body, base + step), minus = reactions(body, base - step);
    for (int l = 0; l < 2; ++l) {
      const double numeric = D.col(l).dot(plus - minus) / (2.0 * h);
      EXPECT_NEAR(S.matrix(l, k), numeric, 1e-5 * std::abs(numeric) + 1e-6) << l << " " << k;
    }
  }
  // How the free nodes follow each motion: the same differences of the equilibria themselves
  // (zero at the prescribed DOFs, which the motion moves).
  for (int k = 0; k < 2; ++k) {
    const Eigen::Vector3d step = k == 0 ? Eigen::Vector3d(0, 0, h) : Eigen::Vector3d(h, 0, 0);
    Eigen::VectorXd plus, minus;
    reactions(body, base + step, &plus);
    reactions(body, base - step, &minus);
    const Eigen::VectorXd numeric = (plus - minus) / (2.0 * h) - D.col(k);
    const Eigen::VectorXd response = S.free_response.col(k);
    EXPECT_LT((response - numeric).cwiseAbs().maxCoeff(), 1e-5 * numeric.cwiseAbs().maxCoeff())
        << "motion " << k;
    EXPECT_GT(numeric.cwiseAbs().maxCoeff(), 0.05) << "the free nodes follow the motion";
  }
  // Symmetric and positive: pulling the top costs energy.
  EXPECT_NEAR(S.matrix(0, 1), S.matrix(1, 0), 1e-9 * S.matrix.norm());
  EXPECT_GT(S.matrix(0, 0), 0.0);
  EXPECT_GT(S.matrix(1, 1), 0.0);
}

TEST(CondensedStiffness, AnExtraPotentialIndefiniteUnprojectedCountsByItsProjectionAlone)
{
  // The isotropic matrix alone: at rest its element stiffnesses are positive semi-definite, so
  // projecting them changes nothing but round-off.
  FiberField fiber(1, 3);
  fiber << 0.3, 0.0, 1.0;
  const HyperelasticBody body(structured_box_mesh({3, 3, 3}, {1.0, 1.0, 1.0}), MaterialParameters{},
                              fiber);
  const TopMoved c = cube_with_top(body.mesh(), Eigen::Vector3d::Zero());
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(body.dof_count(), 1);
  for (int n : c.top)
    D(3 * n + 2, 0) = 1.0;
  int inner = -1;
  for (Eigen::Index n = 0; n < body.mesh().V.rows(); ++n)
    if ((body.mesh().V.row(n) - Eigen::RowVector3d(1.0, 1.0, 1.0) / 3.0).norm() < 1e-9)
      inner = static_cast<int>(n);
  ASSERT_GE(inner, 0);
  // The extra potential's exact block makes K_ff indefinite; its projection (zero) leaves the
  // body's own condensed stiffness.
  const Eigen::VectorXd rest = body.rest_positions();
  const CondensedStiffness plain = condensed_stiffness(body, c.conditions, rest, nullptr, 1.0, D);
  const ligsim::sim::test::IndefiniteUntilProjected extra(inner, 1e6);
  const CondensedStiffness with = condensed_stiffness(body, c.conditions, rest, &extra, 1.0, D);
  EXPECT_EQ(with.factor, "projected");
  EXPECT_NEAR(with.matrix(0, 0), plain.matrix(0, 0), 1e-9 * std::abs(plain.matrix(0, 0)));
}
