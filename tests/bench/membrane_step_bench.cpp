/// Time per step of the membrane tearing scenes (the paper's real-time claim: 1,500 triangles).
/// Run: build-*/tests/sim/membrane/bench_membrane [--benchmark_filter=...]

#include "sim/membrane/crack/direction_search.hpp"
#include "sim/membrane/scene/scene.hpp"
#include "sim/membrane/scene/tear_simulation.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <filesystem>
#include <random>

namespace {

using namespace ligsim::membrane;

Scene square_sheet()
{
  return load_scene(std::filesystem::path(LIGSIM_SOURCE_DIR) / "data" / "scenes" /
                    "square-sheet-45.toml");
}

/// One step (implicit solve, criterion at the tips, tearing) of the 1,500-triangle sheet under
/// load, before it tears: the state is reset every 100 steps so the load stays comparable.
void BM_SquareSheetStepUnderLoad(benchmark::State& state)
{
  TearSimulation loaded(square_sheet());
  for (int step = 0; step < 500; ++step)
    loaded.step();
  TearSimulation simulation = loaded;
  int since_reset = 0;
  for (auto _ : state) {
    simulation.step();
    if (++since_reset == 100) {
      state.PauseTiming();
      simulation = loaded;
      since_reset = 0;
      state.ResumeTiming();
    }
  }
  state.counters["elements"] = simulation.mesh().triangle_count();
  state.counters["cg_iterations"] = simulation.metrics().cg_iterations.back();
}
BENCHMARK(BM_SquareSheetStepUnderLoad)->Unit(benchmark::kMillisecond);

/// The whole 45-degree run, from rest until the sheet is torn in two: the median step time
/// over the run, including the steps that split elements.
void BM_SquareSheetTearingRun(benchmark::State& state)
{
  const Scene scene = square_sheet();
  double median_ms = 0.0, worst_ms = 0.0;
  int steps = 0, events = 0, elements = 0;
  for (auto _ : state) {
    TearSimulation simulation(scene);
    while (!simulation.finished())
      simulation.step();
    std::vector<double> times = simulation.metrics().step_ms;
    std::sort(times.begin(), times.end());
    median_ms = times[times.size() / 2];
    worst_ms = times.back();
    steps = simulation.metrics().steps;
    events = simulation.metrics().propagation_events;
    elements = simulation.mesh().triangle_count();
  }
  state.counters["median_ms_per_step"] = median_ms;
  state.counters["max_ms_per_step"] = worst_ms;
  state.counters["steps"] = steps;
  state.counters["propagation_events"] = events;
  state.counters["elements"] = elements;
}
BENCHMARK(BM_SquareSheetTearingRun)->Unit(benchmark::kMillisecond)->Iterations(3);

/// The direction search at one crack tip (1-degree grid, refinement, exact candidates).
void BM_TipDirectionSearch(benchmark::State& state)
{
  std::mt19937 random(1);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  const TearThresholds thresholds{1.0, 0.1, 1.0, M_PI / 4.0};
  const Eigen::Vector3d stress(value(random), value(random), value(random));
  const Eigen::Vector2d fiber(std::sqrt(0.5), std::sqrt(0.5));
  for (auto _ : state)
    benchmark::DoNotOptimize(
        best_tear_direction(thresholds, stress, fiber, Eigen::Vector2d(0.0, 1.0)));
}
BENCHMARK(BM_TipDirectionSearch)->Unit(benchmark::kMicrosecond);

} // namespace

BENCHMARK_MAIN();
