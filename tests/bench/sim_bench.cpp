// Speed of the simulator: one static solve of the FEBio reference cube (20,480 tets, the
// paper's sec. 5.1 set-up, 0.05 N per top node), and implicit Euler frames of a ligament-sized
// body (a bent 30 x 6 x 3 mm bar of 6,000 tets with 2.9 % in-situ strain, one end fixed, the
// other carried rigidly through 30 degrees of flexion), with both linear solvers.
// Counters: peak_rss_mib is the process's peak resident memory.

#include "common/resources.hpp"
#include "sim/mesh/node_selection.hpp"
#include "sim/mesh/structured_mesh.hpp"
#include "sim/solver/implicit_euler.hpp"
#include "sim/verify/cube_verification.hpp"

#include <benchmark/benchmark.h>
#include <fmt/format.h>

using namespace ligsim::sim;

namespace {

void BM_StaticSolveReferenceCube(benchmark::State& state)
{
  const FebioReference reference = read_febio_reference(LIGSIM_SOURCE_DIR "/data/febio-cube");
  const FebioMesh mesh = read_febio_mesh(reference.mesh_file);
  const FebioCase& c = reference.cases[3]; // par_t005_pen
  NewtonSettings settings;
  settings.load_steps = 1;
  settings.linear_solver = state.range(0) == 0 ? LinearSolverKind::direct : LinearSolverKind::pcg;
  int iterations = 0;
  for (auto _ : state) {
    const CubeCaseResult result =
        run_cube_case(mesh, c, CubeEnergy::matched, settings, ligsim::Points(), 1.0);
    if (!result.converged)
      state.SkipWithError(result.failure.c_str());
    iterations = result.newton_iterations;
  }
  state.counters["newton_iterations"] = iterations;
  state.counters["elements"] = static_cast<double>(mesh.mesh.T.rows());
  state.counters["peak_rss_mib"] = ligsim::peak_rss_mib();
  state.SetLabel(c.name + ", " + to_string(settings.linear_solver));
}
BENCHMARK(BM_StaticSolveReferenceCube)
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_ImplicitFramesLigamentBar(benchmark::State& state)
{
  const ligsim::TetMesh mesh = bent_bar_mesh({40, 6, 5}, {30.0, 6.0, 3.0}, 20.0);
  FiberField fiber(1, 3);
  fiber << 1.029, 0.0, 0.0;
  const HyperelasticBody body(mesh, mcl_material(), fiber);
  BoundaryConditions conditions;
  ConstraintSet tibia;
  tibia.name = "tibia";
  tibia.nodes = nodes_in_box(mesh.V, Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(0.01, 7, 4));
  conditions.constraints.push_back(tibia);
  ConstraintSet femur;
  femur.name = "femur";
  const double far_end = mesh.V.col(0).maxCoeff();
  femur.nodes = nodes_in_box(mesh.V, Eigen::Vector3d(far_end - 1.0, -1, -100),
                             Eigen::Vector3d(far_end + 1, 7, 100));
  RigidMotion flexion;
  flexion.axis = Eigen::Vector3d::UnitY();
  flexion.point_mm = Eigen::Vector3d(20.0, 3.0, 10.0);
  flexion.angle_rad = 30.0 * M_PI / 180.0;
  femur.rigid = flexion;
  conditions.constraints.push_back(femur);

  DynamicsSettings settings;
  constexpr int frames = 60;
  settings.time_step_s = 1.0 / 60.0;
  settings.frames = frames;
  settings.ramp_frames = frames;
  settings.mass_damping_per_s = 10.0;
  settings.linear_solver = state.range(0) == 0 ? LinearSolverKind::direct : LinearSolverKind::pcg;
  settings.pcg.tolerance = 1e-6;
  for (auto _ : state) {
    ImplicitEuler solver(body, conditions, settings);
    Eigen::VectorXd x = body.rest_positions();
    const DynamicResult result = solver.run(x);
    if (!result.completed)
      state.SkipWithError(result.failure.c_str());
    state.counters["cg_iterations_per_frame"] =
        static_cast<double>(result.linear_iterations) / frames;
    state.counters["factorizations"] = result.factorizations;
  }
  state.counters["s_per_frame"] = benchmark::Counter(static_cast<double>(frames),
                                                     benchmark::Counter::kIsIterationInvariantRate |
                                                         benchmark::Counter::kInvert);
  state.counters["elements"] = static_cast<double>(mesh.T.rows());
  state.counters["peak_rss_mib"] = ligsim::peak_rss_mib();
  state.SetLabel(fmt::format("{} frames, {}", frames, to_string(settings.linear_solver)));
}
BENCHMARK(BM_ImplicitFramesLigamentBar)
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

} // namespace

BENCHMARK_MAIN();
