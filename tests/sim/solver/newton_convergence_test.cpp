// Convergence at the round-off floor: stagnation with round-off steps a hair above the
// tolerance converges; stagnation with real steps, or far above the tolerance, does not.

#include "sim/solver/newton_convergence.hpp"

#include <gtest/gtest.h>

using namespace ligsim::sim;

namespace {

IterationFigures figures(double residual, double energy, double step_mm)
{
  IterationFigures f;
  f.relative_residual = residual;
  f.energy_change = energy;
  f.energy_round_off = 1e-12;
  f.displacement_step_mm = step_mm;
  return f;
}

} // namespace

TEST(NewtonConvergence, BelowTheToleranceWithASmallEnergyChangeConverges)
{
  NewtonConvergence convergence(1e-8, 0.0, 1.0);
  convergence.record(figures(1e-3, 1.0, 1e-2));
  EXPECT_EQ(convergence.verdict(1e-3, false), ConvergenceVerdict::iterate);
  convergence.record(figures(1e-10, 1e-12, 1e-9));
  EXPECT_EQ(convergence.verdict(1e-10, false), ConvergenceVerdict::converged);
  EXPECT_EQ(convergence.verdict(1e-3, true), ConvergenceVerdict::converged); // force floor
}

TEST(NewtonConvergence, StagnationAtRoundOffAHairAboveTheToleranceIsTheFloor)
{
  NewtonConvergence convergence(1e-8, 0.0, 1.0);
  convergence.record(figures(1e-2, 1.0, 1e-2));
  for (double r : {1.2e-8, 1.06e-8, 1.05e-8, 1.07e-8}) {
    EXPECT_EQ(convergence.verdict(r, false), ConvergenceVerdict::iterate);
    convergence.record(figures(r, 1e-14, 1e-10));
  }
  EXPECT_EQ(convergence.verdict(1.06e-8, false), ConvergenceVerdict::converged_at_floor);
  const std::string summary = convergence.floor_summary();
  EXPECT_NE(summary.find("1.07e-08"), std::string::npos) << summary;
  EXPECT_NE(summary.find("stagnated over 3 iterations"), std::string::npos) << summary;
}

TEST(NewtonConvergence, StagnationWithRealStepsIsNotTheFloor)
{
  NewtonConvergence energy(1e-8, 0.0, 1.0);
  NewtonConvergence moving(1e-8, 0.0, 1.0);
  for (NewtonConvergence* c : {&energy, &moving})
    c->record(figures(1e-2, 1.0, 1e-2));
  for (int i = 0; i < 4; ++i) {
    energy.record(figures(2e-8, 1e-9, 1e-10)); // energy still changing beyond round-off
    moving.record(figures(2e-8, 1e-14, 1e-6)); // nodes still moving
  }
  EXPECT_EQ(energy.verdict(2e-8, false), ConvergenceVerdict::iterate);
  EXPECT_EQ(moving.verdict(2e-8, false), ConvergenceVerdict::iterate);
}

TEST(NewtonConvergence, FarAboveTheToleranceIsNeverTheFloor)
{
  NewtonConvergence convergence(1e-8, 0.0, 1.0);
  for (int i = 0; i < 6; ++i)
    convergence.record(figures(1e-4, 1e-14, 1e-10));
  EXPECT_EQ(convergence.verdict(1e-4, false), ConvergenceVerdict::iterate);
}

TEST(NewtonConvergence, ProgressIsNotStagnation)
{
  NewtonConvergence convergence(1e-8, 0.0, 1.0);
  convergence.record(figures(1e-6, 1e-14, 1e-10));
  for (double r : {1e-7, 6e-8, 3e-8})
    convergence.record(figures(r, 1e-14, 1e-10));
  EXPECT_EQ(convergence.verdict(3e-8, false), ConvergenceVerdict::iterate);
}
