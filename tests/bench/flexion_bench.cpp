// Interactive knee flexion (implicit Euler frames, the paper's SOFA scene) with and without
// ligament-bone contact, on a built model: frames per second of the frames alone (the solver's
// wall time of the sweep 0 -> 90 degrees at 45 deg/s, 10 ms frames, 200 frames).
// The model folder is $LIGSIM_BENCH_MODEL (default out/mcl6k: the 6,141-tet MCL that
// `ligsim build --config data/vhf-right-knee/mcl.toml --cell-size 1.1 --facet-size 0.95
// --facet-distance 0.08 --out out/mcl6k` writes). Arguments: contact off (0) or on with
// d_hat = arg / 10 mm; linear solves per frame at most ([interactive] max_iterations: 1 is the
// paper's scheme, 12 the default). Run with --benchmark_repetitions=5
// --benchmark_enable_random_interleaving=true on a shared machine and compare medians.

#include "sim/flexion/knee_contact.hpp"
#include "sim/flexion/knee_flexion.hpp"

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <memory>

using namespace ligsim::sim;

namespace {

void BM_InteractiveFlexion(benchmark::State& state)
{
  const char* folder = std::getenv("LIGSIM_BENCH_MODEL");
  const KneeModel model = load_knee_model(folder ? folder : "out/mcl6k");
  FlexionSettings settings;
  settings.mode = FlexionMode::interactive;
  settings.interactive.max_iterations = static_cast<int>(state.range(1));
  settings.angles_deg = {0.0, 90.0};
  settings.axis.posterior = Eigen::Vector3d(0.0, -1.0, 0.0);
  const bool contact_on = state.range(0) > 0;
  settings.contact.enabled = contact_on;
  if (contact_on)
    settings.contact.barrier.d_hat_mm = static_cast<double>(state.range(0)) / 10.0;
  settings.contact.grid.band_mm = std::max(1.0, settings.contact.barrier.d_hat_mm + 0.4);
  const ResolvedAxis axis = resolve_flexion_axis(model, settings.axis);
  const HyperelasticBody body = ligament_body(model, settings.material, settings.in_situ_strain);
  const BoundaryConditions conditions = knee_conditions(model, axis.axis, 90.0);
  const KneeContact contact(model, conditions, settings.contact,
                            std::filesystem::path(folder ? folder : "out/mcl6k") / "contact");
  double fps = 0.0;
  int frames = 0;
  for (auto _ : state) {
    const SweepResult sweep = run_flexion_sweep(body, conditions, settings, {}, &contact);
    if (!sweep.success)
      state.SkipWithError(sweep.failure.c_str());
    fps = sweep.frames_per_second;
    frames = sweep.frames;
  }
  state.counters["frames_per_second"] = fps;
  state.counters["frames"] = frames;
  state.counters["tets"] = body.element_count();
  state.SetLabel((contact_on ? "contact, d_hat " + std::to_string(state.range(0) / 10.0) + " mm"
                             : std::string("no contact")) +
                 ", max_iterations " + std::to_string(state.range(1)));
}
BENCHMARK(BM_InteractiveFlexion)
    ->ArgsProduct({{0, 3, 10}, {1, 12}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

} // namespace

BENCHMARK_MAIN();
