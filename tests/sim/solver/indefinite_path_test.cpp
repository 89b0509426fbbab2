// The cube pushed down along its fibers past its shear (sway) bifurcation: the straight
// equilibrium exists but the tangent stiffness has negative eigenvalues there. The solver must
// converge to it (as FEBio does), say it is unstable with the mode, and a tolerance below what
// floating point gives must end converged-at-floor, not in cut-backs.

#include "sim/mesh/structured_mesh.hpp"
#include "sim/solver/static_solver.hpp"

#include "tests/sim/solver/cube_tension.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace ligsim::sim;

namespace {

FiberField along_z()
{
  FiberField fiber(1, 3);
  fiber << 0, 0, 1;
  return fiber;
}

/// The paper's 0.10 N on each of 289 top nodes of the 1 mm cube, shared by this mesh's nodes.
BoundaryConditions paper_compression(const ligsim::TetMesh& mesh, double per_reference_node_n)
{
  const int top = static_cast<int>(nodes_on_plane(mesh.V, 2, 1.0, 1e-9).size());
  return test::cube_tension(mesh, {0.0, 0.0, -per_reference_node_n * 289.0 / top});
}

double free_residual(const StaticSolver& solver, const Eigen::VectorXd& residual)
{
  double sum = 0.0;
  for (int dof : solver.dofs().free_dofs())
    sum += residual(dof) * residual(dof);
  return std::sqrt(sum);
}

} // namespace

TEST(IndefinitePath, ConvergesToTheStraightEquilibriumPastTheBifurcation)
{
  const ligsim::TetMesh mesh = structured_cube_mesh(4, 1.0);
  const HyperelasticBody body(mesh, mcl_material(), along_z());
  const BoundaryConditions conditions = paper_compression(mesh, 0.10);
  NewtonSettings settings;
  settings.load_steps = 1;
  StaticSolver solver(body, conditions, settings);
  Eigen::VectorXd x = body.rest_positions();
  Eigen::VectorXd residual;
  const StaticResult result = solver.solve(x, [&](const StepReport&, const Eigen::VectorXd&,
                                                  const Eigen::VectorXd& r) { residual = r; });
  ASSERT_TRUE(result.converged) << result.failure;
  EXPECT_LT(free_residual(solver, residual), 1e-8 * 28.9);
  const StepReport& step = result.steps.back();
  EXPECT_GT(step.saddle_iterations, 0);
  EXPECT_GT(step.negative_eigenvalues, 0);
  EXPECT_NE(step.instability.find("bifurcation"), std::string::npos) << step.instability;
  // Straight: the top face moved down without swaying sideways as a whole.
  const Eigen::VectorXd rest = body.rest_positions();
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int node : conditions.loads[0].nodes)
    mean += x.segment<3>(3 * node) - rest.segment<3>(3 * node);
  mean /= static_cast<double>(conditions.loads[0].nodes.size());
  EXPECT_LT(mean.z(), -0.1);
  EXPECT_LT(mean.head<2>().norm(), 1e-3 * std::abs(mean.z()));
}

TEST(IndefinitePath, TheModeOfTheStraightColumnIsOrthogonalToTheLoad)
{
  const ligsim::TetMesh mesh = structured_cube_mesh(4, 1.0);
  const HyperelasticBody body(mesh, mcl_material(), along_z());
  const BoundaryConditions conditions = paper_compression(mesh, 0.10);
  NewtonSettings settings;
  settings.load_steps = 1;
  StaticSolver solver(body, conditions, settings);
  Eigen::VectorXd x = body.rest_positions();
  ASSERT_TRUE(solver.solve(x).converged);
  TangentInertia tangent(body, solver.dofs());
  ASSERT_TRUE(tangent.factorize(x));
  Eigen::VectorXd load = Eigen::VectorXd::Zero(solver.dofs().free_count());
  const Eigen::VectorXd full = solver.dofs().external_forces(conditions);
  for (std::size_t f = 0; f < solver.dofs().free_dofs().size(); ++f)
    load(static_cast<Eigen::Index>(f)) = full(solver.dofs().free_dofs()[f]);
  const StabilityMode mode = tangent.lowest_mode(load);
  EXPECT_GT(mode.negative_eigenvalues, 0);
  EXPECT_EQ(mode.kind(), "bifurcation");
  EXPECT_LT(mode.load_alignment, 0.1);

  // At rest the tangent is positive definite.
  ASSERT_TRUE(tangent.factorize(body.rest_positions()));
  EXPECT_EQ(tangent.negative_eigenvalues(), 0);
}

TEST(IndefinitePath, AToleranceBelowRoundOffEndsConvergedAtTheFloor)
{
  const ligsim::TetMesh mesh = structured_cube_mesh(4, 1.0);
  MaterialParameters stiff = mcl_material();
  stiff.bulk_modulus_mpa = 1e6; // large internal forces: round-off above the absolute floor
  const HyperelasticBody body(mesh, stiff, along_z());
  const BoundaryConditions conditions = paper_compression(mesh, 0.05);
  NewtonSettings settings;
  settings.load_steps = 1;
  settings.residual_tolerance = 1e-14; // below what floating point gives here
  settings.max_iterations = 40;
  StaticSolver solver(body, conditions, settings);
  Eigen::VectorXd x = body.rest_positions();
  const StaticResult result = solver.solve(x);
  ASSERT_TRUE(result.converged) << result.failure;
  EXPECT_EQ(result.cutbacks, 0);
  EXPECT_TRUE(result.steps.back().converged_at_floor);
  EXPECT_NE(result.steps.back().floor.find("stagnated"), std::string::npos);

  // The same state as a reachable tolerance gives.
  settings.residual_tolerance = 1e-10;
  StaticSolver reachable(body, conditions, settings);
  Eigen::VectorXd y = body.rest_positions();
  ASSERT_TRUE(reachable.solve(y).converged);
  EXPECT_LT((x - y).lpNorm<Eigen::Infinity>(), 1e-9);
}
