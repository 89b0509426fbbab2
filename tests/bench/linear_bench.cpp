// Speed of the linear algebra of a Newton step or an implicit Euler frame, on two matrices:
// argument 0, the FEBio reference cube (20,480 tets, 13,872 free DOFs, stiffness at rest of case
// par_t020_pen); argument 1, the MCL model in $LIGSIM_BENCH_MODEL (default out/mcl6k, the
// 6,141-tet build of bench_flexion), stiffness at rest under the flexion supports. Assembling
// the stiffness, factorising it (CHOLMOD's supernodal Cholesky, CHOLMOD's simplicial L D L^T,
// our supernodal L D L^T) and one solve with a factor. Counters: free DOFs, factor entries, the
// factorisation's flops, and the relative residual of a solve.

#include "sim/flexion/knee_flexion.hpp"
#include "sim/solver/stiffness_matrix.hpp"
#include "sim/solver/supernodal_ldlt.hpp"
#include "sim/verify/cube_verification.hpp"

#include <Eigen/CholmodSupport>
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <memory>

using namespace ligsim::sim;

namespace {

/// A body, its supports and its stiffness matrix at rest.
struct Problem {
  Problem(HyperelasticBody body_in, BoundaryConditions conditions_in)
      : body(std::move(body_in))
      , conditions(std::move(conditions_in))
      , dofs(body.node_count(), conditions, body.unreferenced_nodes())
      , stiffness(body.mesh().T, dofs)
  {
    assemble();
  }
  void assemble()
  {
    stiffness.set_zero();
    stiffness.add_elements(body, body.rest_positions(), false);
  }

  HyperelasticBody body;
  BoundaryConditions conditions;
  DofPartition dofs;
  StiffnessMatrix stiffness;
};

std::unique_ptr<Problem> make_cube()
{
  const FebioReference reference = read_febio_reference(LIGSIM_SOURCE_DIR "/data/febio-cube");
  const FebioMesh mesh = read_febio_mesh(reference.mesh_file);
  for (const FebioCase& c : reference.cases)
    if (c.name == "par_t020_pen") {
      FiberField fiber(1, 3);
      fiber.row(0) = c.fiber.normalized().transpose();
      return std::make_unique<Problem>(
          HyperelasticBody(mesh.mesh, cube_material(c, CubeEnergy::matched), fiber),
          cube_conditions(c, mesh.bottom_nodes, mesh.top_nodes));
    }
  throw std::runtime_error("no case par_t020_pen");
}

std::unique_ptr<Problem> make_mcl()
{
  const char* folder = std::getenv("LIGSIM_BENCH_MODEL");
  const KneeModel model = load_knee_model(folder ? folder : "out/mcl6k");
  FlexionSettings settings;
  settings.axis.posterior = Eigen::Vector3d(0.0, -1.0, 0.0);
  const ResolvedAxis axis = resolve_flexion_axis(model, settings.axis);
  return std::make_unique<Problem>(ligament_body(model, settings.material, settings.in_situ_strain),
                                   knee_conditions(model, axis.axis, 90.0));
}

/// The problem of the benchmark's argument, built once.
Problem& problem(const benchmark::State& state)
{
  static std::unique_ptr<Problem> cube, mcl;
  std::unique_ptr<Problem>& chosen = state.range(0) == 0 ? cube : mcl;
  if (!chosen)
    chosen = state.range(0) == 0 ? make_cube() : make_mcl();
  return *chosen;
}

void label(benchmark::State& state)
{
  state.SetLabel(state.range(0) == 0 ? "FEBio cube" : "MCL");
}

double relative_residual(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& x,
                         const Eigen::VectorXd& b)
{
  return (Eigen::VectorXd(A.selfadjointView<Eigen::Lower>() * x) - b).norm() / b.norm();
}

void BM_AssembleStiffness(benchmark::State& state)
{
  Problem& p = problem(state);
  for (auto _ : state)
    p.assemble();
  state.counters["elements"] = p.body.element_count();
  label(state);
}

template <class Factor> void run_factor(benchmark::State& state, Factor& factor)
{
  const Eigen::SparseMatrix<double>& A = problem(state).stiffness.matrix();
  factor.cholmod().nmethods = 1;
  factor.cholmod().method[0].ordering = CHOLMOD_METIS;
  factor.analyzePattern(A);
  for (auto _ : state)
    factor.factorize(A);
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(A.rows());
  state.counters["free_dofs"] = static_cast<double>(A.rows());
  state.counters["residual"] = relative_residual(A, factor.solve(b), b);
  label(state);
}

void BM_FactorCholmodSupernodalLlt(benchmark::State& state)
{
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt;
  run_factor(state, llt);
}

void BM_FactorCholmodSimplicialLdlt(benchmark::State& state)
{
  Eigen::CholmodSimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> ldlt;
  run_factor(state, ldlt);
}

void BM_FactorSupernodalLdlt(benchmark::State& state)
{
  const Eigen::SparseMatrix<double>& A = problem(state).stiffness.matrix();
  SupernodalLdlt ldlt;
  ldlt.analyze(A);
  for (auto _ : state)
    ldlt.factorize(A);
  state.counters["free_dofs"] = static_cast<double>(A.rows());
  state.counters["factor_entries"] = static_cast<double>(ldlt.factor_entries());
  state.counters["gflop"] = ldlt.factorization_flops() * 1e-9;
  label(state);
}

void BM_SolveSupernodalLdlt(benchmark::State& state)
{
  const Eigen::SparseMatrix<double>& A = problem(state).stiffness.matrix();
  SupernodalLdlt ldlt;
  ldlt.analyze(A);
  ldlt.factorize(A);
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(A.rows());
  Eigen::VectorXd x;
  for (auto _ : state)
    benchmark::DoNotOptimize(x = ldlt.solve(b));
  state.counters["residual"] = relative_residual(A, x, b);
  label(state);
}

void BM_MultiplyStiffness(benchmark::State& state)
{
  const StiffnessMatrix& K = problem(state).stiffness;
  const Eigen::VectorXd x = Eigen::VectorXd::Ones(K.matrix().rows());
  Eigen::VectorXd y;
  for (auto _ : state)
    K.multiply(x, y);
  label(state);
}

void BM_AnalyzeSupernodalLdlt(benchmark::State& state)
{
  const Eigen::SparseMatrix<double>& A = problem(state).stiffness.matrix();
  for (auto _ : state) {
    SupernodalLdlt ldlt;
    ldlt.analyze(A);
  }
  label(state);
}

BENCHMARK(BM_AssembleStiffness)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_AnalyzeSupernodalLdlt)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FactorCholmodSupernodalLlt)
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_FactorCholmodSimplicialLdlt)
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_FactorSupernodalLdlt)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SolveSupernodalLdlt)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_MultiplyStiffness)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

} // namespace

BENCHMARK_MAIN();
