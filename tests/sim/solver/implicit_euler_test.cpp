#include "sim/mesh/node_selection.hpp"
#include "sim/mesh/structured_mesh.hpp"
#include "sim/solver/implicit_euler.hpp"
#include "sim/solver/static_solver.hpp"
#include "tests/sim/solver/cube_tension.hpp"
#include "tests/sim/solver/indefinite_until_projected.hpp"

#include <gtest/gtest.h>

using namespace ligsim::sim;

namespace {

struct Cube {
  ligsim::TetMesh mesh = structured_cube_mesh(3, 1.0);
  BoundaryConditions conditions = test::cube_tension(mesh, Eigen::Vector3d(0, 0, 0.2));
};

FiberField along_z()
{
  FiberField fiber(1, 3);
  fiber << 0, 0, 1;
  return fiber;
}

} // namespace

TEST(ImplicitEuler, LumpedMassesAddUpToTheBodyMass)
{
  const Cube cube;
  const HyperelasticBody body(cube.mesh, mcl_material(), along_z());
  DynamicsSettings settings;
  settings.density_kg_m3 = 1100.0;
  const ImplicitEuler solver(body, cube.conditions, settings);
  // 1 mm^3 of 1100 kg/m^3 is 1.1e-9 t in each of the three components.
  EXPECT_NEAR(solver.masses().sum(), 3 * 1.1e-9, 1e-20);
}

TEST(ImplicitEuler, ComesToRestAtTheStaticEquilibrium)
{
  const Cube cube;
  const HyperelasticBody body(cube.mesh, mcl_material(), along_z());
  for (LinearSolverKind kind : {LinearSolverKind::pcg, LinearSolverKind::direct}) {
    DynamicsSettings settings;
    settings.time_step_s = 1e-4;
    settings.frames = 500;
    settings.until_converged = true;
    settings.convergence_tolerance = 1e-9;
    settings.mass_damping_per_s = 1000.0;
    settings.linear_solver = kind;
    settings.pcg.tolerance = 1e-10;
    ImplicitEuler dynamic(body, cube.conditions, settings);
    Eigen::VectorXd x_dynamic = body.rest_positions();
    const DynamicResult result = dynamic.run(x_dynamic);
    ASSERT_TRUE(result.completed) << result.failure;
    EXPECT_TRUE(result.reached_equilibrium);

    StaticSolver quasi_static(body, cube.conditions, NewtonSettings{});
    Eigen::VectorXd x_static = body.rest_positions();
    ASSERT_TRUE(quasi_static.solve(x_static).converged);
    EXPECT_LT((x_dynamic - x_static).lpNorm<Eigen::Infinity>(), 1e-8) << to_string(kind);
  }
}

TEST(ImplicitEuler, HugeTimeStepsStayFiniteAndUninverted)
{
  const Cube cube;
  const HyperelasticBody body(cube.mesh, mcl_material(), along_z());
  DynamicsSettings settings;
  settings.time_step_s = 1.0;
  settings.frames = 10;
  settings.ramp_frames = 5;
  ImplicitEuler solver(body, cube.conditions, settings);
  Eigen::VectorXd x = body.rest_positions();
  double worst_j = 1.0;
  const DynamicResult result =
      solver.run(x, [&](const FrameReport& frame, const Eigen::VectorXd&, const Eigen::VectorXd&) {
        worst_j = std::min(worst_j, frame.min_j);
      });
  ASSERT_TRUE(result.completed) << result.failure;
  EXPECT_TRUE(x.allFinite());
  EXPECT_GT(worst_j, 0.5);
}

TEST(ImplicitEuler, PrescribedRigidMotionIsFollowed)
{
  Cube cube;
  cube.conditions.loads.clear();
  ConstraintSet top;
  top.name = "top";
  top.nodes = nodes_on_plane(cube.mesh.V, 2, 1.0, 1e-9);
  RigidMotion motion;
  motion.axis = Eigen::Vector3d::UnitY();
  motion.point_mm = Eigen::Vector3d(0.5, 0.5, 0.0);
  motion.angle_rad = 0.1;
  top.rigid = motion;
  cube.conditions.constraints.push_back(top);
  const HyperelasticBody body(cube.mesh, mcl_material(), along_z());
  DynamicsSettings settings;
  settings.time_step_s = 1e-3;
  settings.frames = 20;
  settings.ramp_frames = 10;
  settings.mass_damping_per_s = 100.0;
  ImplicitEuler solver(body, cube.conditions, settings);
  Eigen::VectorXd x = body.rest_positions();
  ASSERT_TRUE(solver.run(x).completed);
  for (int node : top.nodes)
    EXPECT_LT(
        (x.segment<3>(3 * node) - motion.apply(cube.mesh.V.row(node).transpose(), 1.0)).norm(),
        1e-12);
}

TEST(ImplicitEuler, AFrameWhoseSolvesRanOutBeforeItsEquationHeldIsFlagged)
{
  const Cube cube;
  const HyperelasticBody body(cube.mesh, mcl_material(), along_z());
  const auto frames_met = [&](int max_iterations, double tolerance) {
    DynamicsSettings settings;
    settings.time_step_s = 1e-2;
    settings.frames = 10;
    settings.ramp_frames = 10;
    settings.linear_solver = LinearSolverKind::direct;
    settings.max_iterations = max_iterations;
    settings.iteration_tolerance = tolerance;
    ImplicitEuler solver(body, cube.conditions, settings);
    Eigen::VectorXd x = body.rest_positions();
    int met = 0;
    const DynamicResult result =
        solver.run(x, [&](const FrameReport& frame, const Eigen::VectorXd&,
                          const Eigen::VectorXd&) { met += frame.equation_met ? 1 : 0; });
    EXPECT_TRUE(result.completed) << result.failure;
    return met;
  };
  EXPECT_EQ(frames_met(8, 0.03), 10);
  // Two solves cannot bring the residual of a 20 % stretch to 1e-13 of the supports' force.
  EXPECT_EQ(frames_met(2, 1e-13), 0);
}

TEST(ImplicitEuler, ASolveIndefiniteWithTheExactExtraBlocksIsRetriedWithTheirProjectionsAlone)
{
  const Cube cube;
  const HyperelasticBody body(cube.mesh, mcl_material(), along_z());
  // An inner node, whose "exact" extra block makes every matrix after the first indefinite.
  int inner = -1;
  for (Eigen::Index n = 0; n < cube.mesh.V.rows(); ++n)
    if ((cube.mesh.V.row(n) - Eigen::RowVector3d(1.0, 1.0, 1.0) / 3.0).norm() < 1e-9)
      inner = static_cast<int>(n);
  ASSERT_GE(inner, 0);
  const test::IndefiniteUntilProjected extra(inner, 1e6);
  const auto run = [&](const ExtraPotential* potential, int max_halvings) {
    DynamicsSettings settings;
    settings.time_step_s = 1e-2;
    settings.frames = 2;
    settings.ramp_frames = 2;
    settings.linear_solver = LinearSolverKind::direct;
    settings.max_iterations = 12;
    settings.iteration_tolerance = 1e-10;
    settings.max_halvings = max_halvings;
    ImplicitEuler solver(body, cube.conditions, settings);
    solver.set_extra_potential(potential);
    Eigen::VectorXd x = body.rest_positions();
    int substeps = 0;
    const DynamicResult result = solver.run(
        x, [&](const FrameReport& frame, const Eigen::VectorXd&, const Eigen::VectorXd&) {
          substeps = std::max(substeps, frame.substeps);
        });
    EXPECT_TRUE(result.completed) << result.failure;
    return std::make_pair(x, substeps);
  };
  const auto [plain, plain_substeps] = run(nullptr, 0);
  // With no halving left, the frame's later solves take the projected blocks (zero) alone.
  const auto [projected, unhalved] = run(&extra, 0);
  EXPECT_EQ(unhalved, 1);
  // With halvings left, the sub-step is halved first; the same state either way (the potential
  // has no energy), to the frames' tolerance.
  const auto [halved, substeps] = run(&extra, 3);
  EXPECT_GT(substeps, 1);
  const double moved = (plain - body.rest_positions()).lpNorm<Eigen::Infinity>();
  EXPECT_GT(moved, 1e-3);
  EXPECT_LT((projected - plain).lpNorm<Eigen::Infinity>(), 1e-6 * moved);
  EXPECT_LT((halved - plain).lpNorm<Eigen::Infinity>(), 1e-6 * moved);
}

TEST(ImplicitEuler, StiffnessDampingRelaxesTheCubeAsKelvinVoigtDoes)
{
  // Rayleigh's beta K v as a dissipation potential. The 1 mm cube's inertia is negligible at
  // these time steps (its period is about 1e-6 s), so the motion is K beta v = f - K u: the
  // distance to equilibrium falls as exp(-t / beta), and by backward Euler's factor
  // 1 / (1 + h / beta) per frame. Without beta it is there within a few frames.
  const Cube cube;
  const HyperelasticBody body(cube.mesh, mcl_material(), along_z());
  StaticSolver quasi_static(body, cube.conditions, NewtonSettings{});
  Eigen::VectorXd x_static = body.rest_positions();
  ASSERT_TRUE(quasi_static.solve(x_static).converged);
  const double h = 1e-5, beta = 1e-4;
  const auto run = [&](double damping, std::vector<double>& distance) {
    DynamicsSettings settings;
    settings.time_step_s = h;
    settings.frames = 400;
    settings.until_converged = true;
    settings.convergence_tolerance = 1e-8;
    settings.stiffness_damping_s = damping;
    settings.linear_solver = LinearSolverKind::direct;
    settings.max_iterations = 8;
    settings.iteration_tolerance = 1e-10;
    ImplicitEuler solver(body, cube.conditions, settings);
    Eigen::VectorXd x = body.rest_positions();
    const DynamicResult result = solver.run(
        x, [&](const FrameReport&, const Eigen::VectorXd& state, const Eigen::VectorXd&) {
          distance.push_back((state - x_static).lpNorm<Eigen::Infinity>());
        });
    EXPECT_TRUE(result.completed) << "beta " << damping << ": " << result.failure;
    EXPECT_LT((x - x_static).lpNorm<Eigen::Infinity>(), 1e-7) << "beta " << damping;
  };
  std::vector<double> undamped, damped;
  run(0.0, undamped);
  run(beta, damped);
  EXPECT_LE(undamped.size(), 10u);
  ASSERT_GT(damped.size(), 100u);
  // Near equilibrium, where the material is linear to 1e-4 over the remaining distance.
  const double factor = 1.0 / (1.0 + h / beta);
  for (std::size_t frame = 50; frame <= 100; frame += 10)
    EXPECT_NEAR(damped[frame + 1] / damped[frame], factor, 5e-4 * factor) << "frame " << frame;
}
