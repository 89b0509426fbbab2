#include "common/error.hpp"
#include "sim/mesh/structured_mesh.hpp"
#include "sim/solver/arc_length.hpp"
#include "sim/solver/extra_potential.hpp"
#include "sim/solver/static_solver.hpp"

#include "tests/sim/solver/cube_tension.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace ligsim::sim;

namespace {

/// The von Mises truss: two bars (axial stiffness EA, Green strain, energy EA L0 / 2 eps^2) from
/// supports at (-L, 0) and (L, 0) to the apex, at (0, h) at rest, pushed down by lambda P. The
/// unknowns are the apex's (x, z). With the apex on the axis, E = EA / (4 L0^3) (z^2 - h^2)^2,
/// so lambda P = EA / L0^3 (h^2 - z^2) z: a maximum at z = h / sqrt(3), the limit load
/// 2 EA h^3 / (3 sqrt(3) L0^3), and a minimum (its negative) at z = -h / sqrt(3), where the
/// snapped-through truss climbs again.
class VonMisesTruss : public EquilibriumSystem {
public:
  static constexpr double EA = 1000.0; // N
  static constexpr double L = 10.0;    // mm
  static constexpr double h = 1.0;     // mm
  static constexpr double P = 1.0;     // N, above the limit load
  static double L0() { return std::sqrt(L * L + h * h); }
  static double limit_load()
  {
    return 2.0 * EA * h * h * h / (3.0 * std::sqrt(3.0) * std::pow(L0(), 3));
  }

  VonMisesTruss()
      : m_load(Eigen::Vector2d(0.0, -P))
  {
  }
  Eigen::Index size() const override { return 2; }
  const Eigen::VectorXd& load() const override { return m_load; }
  bool internal_force(const Eigen::VectorXd& u, Eigen::VectorXd& g) const override
  {
    g = Eigen::Vector2d::Zero();
    for (double side : {-1.0, 1.0}) {
      const Eigen::Vector2d d = u - Eigen::Vector2d(side * L, 0.0);
      const double strain = (d.squaredNorm() - L0() * L0()) / (2.0 * L0() * L0());
      g += EA * L0() * strain * d / (L0() * L0());
    }
    return true;
  }
  void tangent(const Eigen::VectorXd& u, Eigen::SparseMatrix<double>& K) const override
  {
    Eigen::Matrix2d dense = Eigen::Matrix2d::Zero();
    for (double side : {-1.0, 1.0}) {
      const Eigen::Vector2d d = u - Eigen::Vector2d(side * L, 0.0);
      const double L02 = L0() * L0();
      const double strain = (d.squaredNorm() - L02) / (2.0 * L02);
      dense += EA * L0() *
               (d * d.transpose() / (L02 * L02) + strain * Eigen::Matrix2d::Identity() / L02);
    }
    K = dense.triangularView<Eigen::Lower>().toDenseMatrix().sparseView();
  }

private:
  Eigen::VectorXd m_load;
};

/// The truss's bars as an extra potential on node 0 of a body (x and z of the node).
class TrussPotential : public ExtraPotential {
public:
  double energy(const Eigen::VectorXd& x, double, Eigen::VectorXd* gradient) const override
  {
    const Eigen::Vector2d apex(x(0), x(2));
    double energy = 0.0;
    for (double side : {-1.0, 1.0}) {
      const Eigen::Vector2d d = apex - Eigen::Vector2d(side * VonMisesTruss::L, 0.0);
      const double L02 = VonMisesTruss::L0() * VonMisesTruss::L0();
      const double strain = (d.squaredNorm() - L02) / (2.0 * L02);
      energy += 0.5 * VonMisesTruss::EA * VonMisesTruss::L0() * strain * strain;
    }
    if (gradient) {
      Eigen::VectorXd g;
      m_truss.internal_force(apex, g);
      (*gradient)(0) += g(0);
      (*gradient)(2) += g(1);
    }
    return energy;
  }
  void hessian_blocks(const Eigen::VectorXd& x, double, bool,
                      std::vector<NodeBlock>& blocks) const override
  {
    Eigen::SparseMatrix<double> K;
    m_truss.tangent(Eigen::Vector2d(x(0), x(2)), K);
    const Eigen::Matrix2d lower = Eigen::Matrix2d(K);
    NodeBlock block;
    block.node = 0;
    block.block(0, 0) = lower(0, 0);
    block.block(2, 0) = block.block(0, 2) = lower(1, 0);
    block.block(2, 2) = lower(1, 1);
    blocks.push_back(block);
  }
  double max_step(const Eigen::VectorXd&, const Eigen::VectorXd&, double) const override
  {
    return 1.0;
  }
  int make_admissible(Eigen::VectorXd&, double) const override { return 0; }

private:
  VonMisesTruss m_truss;
};

/// Apex height where lambda P = EA / L0^3 (h^2 - z^2) z on the branch z < -h / sqrt(3).
double snapped_height(double force)
{
  const double c = force * std::pow(VonMisesTruss::L0(), 3) / VonMisesTruss::EA;
  double lo = -2.0 * VonMisesTruss::h;
  double hi = -VonMisesTruss::h / std::sqrt(3.0);
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    ((VonMisesTruss::h * VonMisesTruss::h - mid * mid) * mid > c ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

/// The truss in the load-controlled StaticSolver in `load_steps` equal steps: its apex is node 0
/// of one tet whose other nodes are fixed (a ground substance 1e-6 of the truss's stiffness), the
/// bars an extra potential on that node, the apex held in the truss's plane.
struct TrussOnATet {
  StaticResult result;
  Eigen::VectorXd x;
};

TrussOnATet solve_truss_on_a_tet(int load_steps)
{
  ligsim::TetMesh mesh;
  mesh.V.resize(4, 3);
  const double h = VonMisesTruss::h;
  mesh.V << 0, 0, h, 1, 0, h + 1, 0, 1, h + 1, 0, 0, h + 1;
  mesh.T.resize(1, 4);
  mesh.T << 0, 1, 2, 3;
  MaterialParameters soft;
  soft.mu_mpa = 1e-6;
  soft.bulk_modulus_mpa = 1e-5;
  soft.fiber.reset();
  const HyperelasticBody body(mesh, soft, FiberField());
  BoundaryConditions conditions;
  conditions.constraints.push_back({"tet", {1, 2, 3}, {true, true, true}, {}, {}});
  conditions.constraints.push_back({"plane", {0}, {false, true, false}, {}, {}});
  conditions.loads.push_back({"apex", {0}, Eigen::Vector3d(0, 0, -VonMisesTruss::P)});
  const TrussPotential truss;
  NewtonSettings settings;
  settings.load_steps = load_steps;
  StaticSolver solver(body, conditions, settings);
  solver.set_extra_potential(&truss);
  TrussOnATet solved;
  solved.x = body.rest_positions();
  solved.result = solver.solve(solved.x);
  return solved;
}

/// Converged on the snapped branch at full load, the apex on the axis (the tet's ground substance
/// moves it by ~1e-7 mm).
void expect_snapped(const TrussOnATet& solved)
{
  ASSERT_TRUE(solved.result.converged) << solved.result.failure;
  EXPECT_NEAR(solved.x(2), snapped_height(VonMisesTruss::P), 1e-5);
  EXPECT_NEAR(solved.x(0), 0.0, 1e-9);
}

/// A per-step count summed over the solve's load steps.
int total(const StaticResult& result, int StepReport::*count)
{
  int sum = 0;
  for (const StepReport& step : result.steps)
    sum += step.*count;
  return sum;
}

} // namespace

TEST(ArcLength, LoadControlJumpsOverTheTrussLimitPointWithoutSeeingIt)
{
  // The truss in 4 load steps of 0.25 (the limit is at 0.379): the Newton step of the second one
  // lands beyond the unstable branch, on the snapped one, and every matrix on the way is
  // positive definite, so the solver converges there without ever meeting the limit point (a
  // snap-through, which a dynamic run would show as a jump). Only the continuation finds the
  // limit load.
  const TrussOnATet solved = solve_truss_on_a_tet(4);
  expect_snapped(solved);
  EXPECT_EQ(total(solved.result, &StepReport::indefinite_iterations), 0);
}

TEST(ArcLength, LoadControlInSmallStepsSnapsThroughByShiftedNewtonSteps)
{
  // The truss in 20 load steps of 0.05: the step from 0.35 to 0.40 crosses the limit point,
  // where the near equilibrium vanishes and the bars' Hessian is indefinite (it has no positive
  // semi-definite form: the Newton step fails and so does every cut-back). The retry with
  // shifted Newton steps descends the energy to the snapped equilibrium, as a dynamic run would
  // jump there.
  const TrussOnATet solved = solve_truss_on_a_tet(20);
  expect_snapped(solved);
  EXPECT_GT(total(solved.result, &StepReport::shifted_iterations), 0);
}

TEST(ArcLength, PassesBothTrussLimitPointsAndFindsTheSnappedEquilibrium)
{
  const VonMisesTruss truss;
  Eigen::VectorXd u = Eigen::Vector2d(0.0, VonMisesTruss::h);
  ArcLengthSettings settings;
  settings.first_load_increment = 0.02;
  const ArcLengthResult result = follow_path(truss, u, settings);
  ASSERT_TRUE(result.reached) << result.failure;

  const double limit = VonMisesTruss::limit_load() / VonMisesTruss::P;
  ASSERT_EQ(result.critical_points.size(), 2u);
  EXPECT_EQ(result.critical_points[0].kind, "limit point");
  EXPECT_NEAR(result.critical_points[0].load_factor, limit, 5e-4 * limit); // measured 1.5e-4
  EXPECT_EQ(result.critical_points[1].kind, "limit point");
  EXPECT_NEAR(result.critical_points[1].load_factor, -limit, 5e-4 * limit);
  // The tangent has one negative eigenvalue between the limit points, none outside them.
  int max_negative = 0;
  for (const PathPoint& point : result.path)
    max_negative = std::max(max_negative, point.negative_eigenvalues);
  EXPECT_EQ(max_negative, 1);
  EXPECT_EQ(result.path.front().negative_eigenvalues, 0);
  EXPECT_EQ(result.path.back().negative_eigenvalues, 0);

  // Equilibrium at the full load on the snapped branch, the apex on the axis.
  EXPECT_NEAR(u(0), 0.0, 1e-9);
  EXPECT_NEAR(u(1), snapped_height(VonMisesTruss::P), 1e-9);
}

TEST(ArcLength, TheLimitLoadConvergesWithTheArcLength)
{
  // The limit point is the vertex of a parabola through three path points: its error falls
  // with the cube of the arc (measured: 1.5e-3, 3e-5, 4e-9 for first increments 0.2, 0.05,
  // 0.005 at a fixed arc).
  const VonMisesTruss truss;
  const double limit = VonMisesTruss::limit_load() / VonMisesTruss::P;
  for (const auto& [first, tolerance] :
       std::vector<std::pair<double, double>>{{0.2, 5e-3}, {0.05, 1e-4}, {0.005, 1e-7}}) {
    Eigen::VectorXd u = Eigen::Vector2d(0.0, VonMisesTruss::h);
    ArcLengthSettings settings;
    settings.first_load_increment = first;
    settings.max_arc_growth = 1.0;
    const ArcLengthResult result = follow_path(truss, u, settings);
    ASSERT_TRUE(result.reached) << first << ": " << result.failure;
    ASSERT_FALSE(result.critical_points.empty());
    EXPECT_NEAR(result.critical_points[0].load_factor, limit, tolerance * limit) << first;
  }
}

TEST(ArcLength, FactorisesTheTangentOncePerConvergedPoint)
{
  // The tangent factorised at a converged point gives its inertia and the next predictor; it is
  // not factorised again at the top of the next step. Tangents: the start, one per corrector
  // iteration (Newton at the target included), one per converged point, one at the target.
  class CountingTruss : public VonMisesTruss {
  public:
    void tangent(const Eigen::VectorXd& u, Eigen::SparseMatrix<double>& K) const override
    {
      ++evaluations;
      VonMisesTruss::tangent(u, K);
    }
    mutable int evaluations = 0;
  };
  const CountingTruss truss;
  Eigen::VectorXd u = Eigen::Vector2d(0.0, VonMisesTruss::h);
  ArcLengthSettings settings;
  settings.first_load_increment = 0.02;
  const ArcLengthResult result = follow_path(truss, u, settings);
  ASSERT_TRUE(result.reached) << result.failure;
  const int converged_points = static_cast<int>(result.path.size()) - 1; // the start excluded
  EXPECT_EQ(truss.evaluations, 1 + result.newton_iterations + converged_points + 1);
}

TEST(ArcLength, AgreesWithTheLoadControlledSolverWhereThePathIsStable)
{
  const ligsim::TetMesh mesh = structured_cube_mesh(3, 1.0);
  FiberField fiber(1, 3);
  fiber << 0, 0, 1;
  const HyperelasticBody body(mesh, mcl_material(), fiber);
  const BoundaryConditions conditions = test::cube_tension(mesh, {0.02, 0.0, 0.3});

  StaticSolver solver(body, conditions, NewtonSettings{});
  Eigen::VectorXd x = body.rest_positions();
  ASSERT_TRUE(solver.solve(x).converged);

  const BodyEquilibrium system(body, conditions);
  Eigen::VectorXd u = system.rest_unknowns();
  const ArcLengthResult result = follow_path(system, u);
  ASSERT_TRUE(result.reached) << result.failure;
  EXPECT_TRUE(result.critical_points.empty());
  EXPECT_LT((system.positions(u) - x).lpNorm<Eigen::Infinity>(), 1e-8);
  for (std::size_t i = 1; i < result.path.size(); ++i)
    EXPECT_GT(result.path[i].load_factor, result.path[i - 1].load_factor);
}

TEST(ArcLength, MovingSupportsAreRejected)
{
  const ligsim::TetMesh mesh = structured_cube_mesh(2, 1.0);
  FiberField fiber(1, 3);
  fiber << 0, 0, 1;
  const HyperelasticBody body(mesh, mcl_material(), fiber);
  BoundaryConditions conditions = test::cube_tension(mesh, {0, 0, 0.1});
  conditions.constraints[0].displacement_mm = Eigen::Vector3d(0, 0, -0.1);
  EXPECT_THROW(BodyEquilibrium(body, conditions), ligsim::InputError);
}
