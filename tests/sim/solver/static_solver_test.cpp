#include "common/error.hpp"
#include "sim/mesh/node_selection.hpp"
#include "sim/mesh/structured_mesh.hpp"
#include "sim/solver/static_solver.hpp"

#include "tests/sim/solver/cube_tension.hpp"
#include <Eigen/Geometry>

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace ligsim::sim;

namespace {

FiberField along_z()
{
  FiberField fiber(1, 3);
  fiber << 0, 0, 1;
  return fiber;
}

struct Solved {
  StaticResult result;
  Eigen::VectorXd x;
  Eigen::VectorXd residual;
  Eigen::VectorXd rest; ///< where x started
};

Solved solve(const HyperelasticBody& body, const BoundaryConditions& conditions,
             const NewtonSettings& settings)
{
  StaticSolver solver(body, conditions, settings);
  Solved solved;
  solved.rest = body.rest_positions();
  solved.x = solved.rest;
  solved.result = solver.solve(solved.x, [&](const StepReport&, const Eigen::VectorXd&,
                                             const Eigen::VectorXd& r) { solved.residual = r; });
  return solved;
}

/// A cube of `cells`^3 cells pulled along its fibers by `per_node_n` on each top node in one load
/// step with `max_iterations` Newton iterations.
Solved pull_in_one_step(int cells, double per_node_n, int max_iterations,
                        NewtonSettings settings = {})
{
  const ligsim::TetMesh mesh = structured_cube_mesh(cells, 1.0);
  const HyperelasticBody body(mesh, mcl_material(), along_z());
  const BoundaryConditions conditions = test::cube_tension(mesh, {0.0, 0.0, per_node_n});
  settings.load_steps = 1;
  settings.max_iterations = max_iterations;
  return solve(body, conditions, settings);
}

/// The unit cube's surface nodes moved as one rigid body by `motion`.
BoundaryConditions surface_moved(const ligsim::TetMesh& mesh, const RigidMotion& motion)
{
  ConstraintSet surface;
  surface.name = "surface";
  for (Eigen::Index n = 0; n < mesh.V.rows(); ++n) {
    const Eigen::Vector3d p = mesh.V.row(n);
    if ((p.array() < 1e-9).any() || (p.array() > 1 - 1e-9).any())
      surface.nodes.push_back(static_cast<int>(n));
  }
  surface.rigid = motion;
  BoundaryConditions conditions;
  conditions.constraints.push_back(surface);
  return conditions;
}

} // namespace

TEST(StaticSolver, ReactionsBalanceTheLoad)
{
  const ligsim::TetMesh mesh = structured_cube_mesh(4, 1.0);
  const HyperelasticBody body(mesh, mcl_material(), along_z());
  const BoundaryConditions conditions = test::cube_tension(mesh, {0.01, 0.0, 0.2});
  const Solved solved = solve(body, conditions, NewtonSettings{});
  ASSERT_TRUE(solved.result.converged) << solved.result.failure;
  const Eigen::Vector3d applied = 25.0 * Eigen::Vector3d(0.01, 0.0, 0.2);
  const Eigen::Vector3d reaction = reaction_forces(conditions, solved.residual)[0];
  EXPECT_LT((reaction + applied).norm(), 1e-7 * applied.norm());
  EXPECT_GT(solved.result.steps.back().strain_energy_mj, 0.0);
}

TEST(StaticSolver, DirectAndPcgFindTheSameEquilibrium)
{
  const ligsim::TetMesh mesh = structured_cube_mesh(3, 1.0);
  const HyperelasticBody body(mesh, mcl_material(), along_z());
  const BoundaryConditions conditions = test::cube_tension(mesh, {0.0, 0.0, 0.3});
  NewtonSettings settings;
  settings.load_steps = 2;
  const Solved direct = solve(body, conditions, settings);
  settings.linear_solver = LinearSolverKind::pcg;
  settings.pcg.tolerance = 1e-10;
  const Solved pcg = solve(body, conditions, settings);
  ASSERT_TRUE(direct.result.converged && pcg.result.converged);
  EXPECT_GT(pcg.result.linear_iterations, 0);
  EXPECT_LT((direct.x - pcg.x).lpNorm<Eigen::Infinity>(), 1e-9);
}

TEST(StaticSolver, RigidMotionOfTheWholeBoundaryCostsNoEnergy)
{
  const ligsim::TetMesh mesh = structured_cube_mesh(3, 1.0);
  const HyperelasticBody body(mesh, mcl_material(), along_z());
  RigidMotion motion;
  motion.axis = Eigen::Vector3d(1, 1, 0).normalized();
  motion.point_mm = Eigen::Vector3d(2, 0, 0);
  motion.angle_rad = 1.5;
  motion.translation_mm = Eigen::Vector3d(0.5, -1, 2);
  const BoundaryConditions conditions = surface_moved(mesh, motion);
  NewtonSettings settings;
  settings.load_steps = 6;
  const Solved solved = solve(body, conditions, settings);
  ASSERT_TRUE(solved.result.converged) << solved.result.failure;
  EXPECT_LT(solved.result.steps.back().strain_energy_mj, 1e-12);
  for (Eigen::Index n = 0; n < mesh.V.rows(); ++n) {
    const Eigen::Vector3d expected = motion.apply(mesh.V.row(n).transpose(), 1.0);
    EXPECT_LT((solved.x.segment<3>(3 * n) - expected).norm(), 1e-8) << "node " << n;
  }
}

TEST(StaticSolver, AMoveFromAStateWithAnInvertedElementFailsSayingSo)
{
  // The prescribed nodes' move predicts the free ones from the stiffness at the start: an
  // inverted element there has none (its Hessian was once read uninitialised).
  const ligsim::TetMesh mesh = structured_cube_mesh(3, 1.0);
  const HyperelasticBody body(mesh, mcl_material(), along_z());
  RigidMotion motion;
  motion.translation_mm = Eigen::Vector3d(0.1, 0, 0);
  const BoundaryConditions conditions = surface_moved(mesh, motion);
  const int inside = 21; // (1, 1, 1) of the 4 x 4 x 4 nodes: not on the surface
  ASSERT_LT((mesh.V.row(inside).array() - 1.0 / 3.0).abs().maxCoeff(), 1e-12);
  NewtonSettings settings;
  settings.load_steps = 1;
  settings.max_cutbacks = 2;
  StaticSolver solver(body, conditions, settings);
  Eigen::VectorXd x = body.rest_positions();
  x.segment<3>(3 * inside) += Eigen::Vector3d(2, 2, 2);
  ASSERT_FALSE(std::isfinite(body.energy(x).energy));
  const StaticResult result = solver.solve(x);
  EXPECT_FALSE(result.converged);
  EXPECT_NE(result.failure.find("the state they move from is not admissible (element "),
            std::string::npos)
      << result.failure;
}

TEST(StaticSolver, CutsBackALoadStepThatFails)
{
  const Solved solved = pull_in_one_step(3, 6.0, 4); // too few iterations for the load at once
  ASSERT_TRUE(solved.result.converged) << solved.result.failure;
  EXPECT_GT(solved.result.cutbacks, 0);
  EXPECT_GT(solved.result.steps.back().substeps, 1);
}

TEST(StaticSolver, ALoadStepThatNeedsMoreSubStepsThanAllowedStops)
{
  // The step of CutsBackALoadStepThatFails with at most one sub-step: its first fails, and the
  // solve stops there, saying why, instead of cutting back.
  NewtonSettings one_substep;
  one_substep.max_substeps = 1;
  const Solved solved = pull_in_one_step(3, 6.0, 4, one_substep);
  EXPECT_FALSE(solved.result.converged);
  EXPECT_NE(solved.result.failure.find("1 sub-steps, the most one load step may take"),
            std::string::npos)
      << solved.result.failure;
  EXPECT_TRUE(solved.x.isApprox(solved.rest));
}

TEST(StaticSolver, ReportsFailureWithTheLastGoodState)
{
  NewtonSettings one_cutback;
  one_cutback.max_cutbacks = 1;
  const Solved solved = pull_in_one_step(2, 20.0, 1, one_cutback);
  EXPECT_FALSE(solved.result.converged);
  EXPECT_NE(solved.result.failure.find("cut-backs"), std::string::npos) << solved.result.failure;
  EXPECT_TRUE(solved.x.isApprox(solved.rest));
}

TEST(StaticSolver, NodesWithoutElementsAreHeldFixed)
{
  ligsim::TetMesh mesh = structured_cube_mesh(2, 1.0);
  mesh.V.conservativeResize(mesh.V.rows() + 1, 3);
  mesh.V.row(mesh.V.rows() - 1) << 5.0, 5.0, 5.0;
  const HyperelasticBody body(mesh, mcl_material(), along_z());
  EXPECT_TRUE(body.unreferenced_nodes().back());
  const Solved solved = solve(body, test::cube_tension(mesh, {0, 0, 0.1}), NewtonSettings{});
  ASSERT_TRUE(solved.result.converged) << solved.result.failure;
  EXPECT_EQ(solved.x.tail<3>(), Eigen::Vector3d(5, 5, 5));
}

TEST(StaticSolver, ConflictingConstraintsAreRejected)
{
  const ligsim::TetMesh mesh = structured_cube_mesh(2, 1.0);
  BoundaryConditions conditions = test::cube_tension(mesh, {0, 0, 0.1});
  ConstraintSet again = conditions.constraints[0];
  again.name = "again";
  again.displacement_mm = Eigen::Vector3d(0, 0, 0.1);
  conditions.constraints.push_back(again);
  EXPECT_THROW(DofPartition(static_cast<int>(mesh.V.rows()), conditions, {}), ligsim::InputError);
}

TEST(StaticSolver, ExplicitLoadFactorsReachTheSameEquilibrium)
{
  const ligsim::TetMesh mesh = structured_cube_mesh(3, 1.0);
  const HyperelasticBody body(mesh, mcl_material(), along_z());
  const BoundaryConditions conditions = test::cube_tension(mesh, {0.0, 0.0, 0.3});
  NewtonSettings uniform;
  uniform.load_steps = 4;
  NewtonSettings listed;
  listed.load_factors = {0.0, 0.1, 0.7, 1.0};
  const Solved a = solve(body, conditions, uniform);
  const Solved b = solve(body, conditions, listed);
  ASSERT_TRUE(a.result.converged && b.result.converged) << b.result.failure;
  ASSERT_EQ(b.result.steps.size(), 4u);
  // The leading 0 is an equilibrium in place: nothing is loaded, nothing moves.
  EXPECT_EQ(b.result.steps[0].load_factor, 0.0);
  EXPECT_NEAR(b.result.steps[0].strain_energy_mj, 0.0, 1e-15);
  EXPECT_EQ(b.result.steps[2].load_factor, 0.7);
  EXPECT_LT((a.x - b.x).lpNorm<Eigen::Infinity>(), 1e-9);
}

TEST(StaticSolver, AStepStartsFromItsGuessAndFromThePathWhereTheGuessFails)
{
  const ligsim::TetMesh mesh = structured_cube_mesh(3, 1.0);
  const HyperelasticBody body(mesh, mcl_material(), along_z());
  const BoundaryConditions conditions = test::cube_tension(mesh, {0.0, 0.0, 0.3});
  NewtonSettings settings;
  settings.load_steps = 3;
  std::vector<Eigen::VectorXd> equilibria;
  StaticSolver along(body, conditions, settings);
  Eigen::VectorXd x = body.rest_positions();
  ASSERT_TRUE(along
                  .solve(x, [&](const StepReport&, const Eigen::VectorXd& state,
                                const Eigen::VectorXd&) { equilibria.push_back(state); })
                  .converged);

  // Each step's own equilibrium as its guess: nothing left to iterate.
  StaticSolver guessed(body, conditions, settings);
  guessed.set_step_starts(equilibria);
  Eigen::VectorXd y = body.rest_positions();
  const StaticResult from_guesses = guessed.solve(y);
  ASSERT_TRUE(from_guesses.converged) << from_guesses.failure;
  for (const StepReport& step : from_guesses.steps) {
    EXPECT_EQ(step.iterations, 0) << step.step;
    EXPECT_EQ(step.substeps, 1) << step.step;
  }
  EXPECT_LT((y - x).lpNorm<Eigen::Infinity>(), 1e-12);

  // A guess with an inverted element cannot be solved from: the step goes on from the last
  // state, to the same equilibrium.
  std::vector<Eigen::VectorXd> bad = {Eigen::VectorXd(), -equilibria[1], Eigen::VectorXd()};
  StaticSolver recovering(body, conditions, settings);
  recovering.set_step_starts(bad);
  Eigen::VectorXd z = body.rest_positions();
  const StaticResult recovered = recovering.solve(z);
  ASSERT_TRUE(recovered.converged) << recovered.failure;
  EXPECT_GT(recovered.steps[1].iterations, 0);
  EXPECT_LT((z - x).lpNorm<Eigen::Infinity>(), 1e-8);
}

TEST(StaticSolver, LoadFactorsMustIncreaseWithinZeroAndOne)
{
  const ligsim::TetMesh mesh = structured_cube_mesh(2, 1.0);
  const HyperelasticBody body(mesh, mcl_material(), along_z());
  const BoundaryConditions conditions = test::cube_tension(mesh, {0.0, 0.0, 0.1});
  for (const std::vector<double>& factors :
       {std::vector<double>{0.5, 0.2}, {0.5, 0.5}, {0.5, 1.5}, {-0.1, 1.0}}) {
    NewtonSettings settings;
    settings.load_factors = factors;
    EXPECT_THROW(StaticSolver(body, conditions, settings), ligsim::InputError);
  }
}
