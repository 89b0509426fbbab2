/// A hand pulling a membrane: the nodes it holds follow it at its speed, a crack's copies of them
/// too, they go free when it lets go; and a sheet held at one side and pulled by the hand at the
/// other tears from its slit.

#include "sim/membrane/scene/scene.hpp"
#include "sim/membrane/scene/tear_simulation.hpp"

#include <gtest/gtest.h>

#include <filesystem>

namespace ligsim::membrane {
namespace {

/// The 45-degree square sheet with its left side held and no pull of its own.
Scene held_sheet()
{
  return load_scene(std::filesystem::path(LIGSIM_SOURCE_DIR) / "data" / "scenes" /
                    "square-sheet-held.toml");
}

} // namespace

TEST(Hand, HeldNodesFollowTheHandAtItsSpeedAndGoFreeWhenItLetsGo)
{
  TearSimulation simulation(held_sheet());
  EXPECT_FALSE(simulation.grab(Vec2(20.0, 0.0), 0.6, 0.5, 10.0)) << "nothing near";
  ASSERT_TRUE(simulation.grab(Vec2(5.0, 0.0), 0.6, 0.5, 10.0));
  const std::vector<int> held = simulation.hand()->nodes();
  ASSERT_GE(held.size(), 3u);
  const Vec2 start = simulation.hand()->position();
  std::vector<Vec2> before;
  for (int v : held)
    before.push_back(simulation.mesh().position[v]);
  // 1 mm to the right at 10 mm/s: 0.2 mm after 20 steps of 1 ms, all of it after 100.
  simulation.move_hand(start + Vec2(1.0, 0.0));
  for (int s = 0; s < 20; ++s)
    simulation.step();
  for (std::size_t k = 0; k < held.size(); ++k)
    EXPECT_LT((simulation.mesh().position[held[k]] - before[k] - Vec2(0.2, 0.0)).norm(), 1e-12);
  for (int s = 0; s < 100; ++s)
    simulation.step();
  for (std::size_t k = 0; k < held.size(); ++k)
    EXPECT_LT((simulation.mesh().position[held[k]] - before[k] - Vec2(1.0, 0.0)).norm(), 1e-12);
  simulation.release();
  EXPECT_FALSE(simulation.hand().has_value());
  for (int v : held)
    EXPECT_EQ(simulation.mesh().constraint[v], NodeConstraint::free);
}

TEST(Hand, ASheetHeldAtOneSideAndPulledAtTheOtherTearsFromItsSlit)
{
  TearSimulation simulation(held_sheet());
  // The right side's middle, pulled 4 mm outward at 10 mm/s.
  ASSERT_TRUE(simulation.grab(Vec2(5.0, 0.0), 2.0, 0.5, 10.0));
  simulation.move_hand(simulation.hand()->position() + Vec2(4.0, 0.0));
  for (int s = 0; s < 400 && simulation.metrics().events.empty(); ++s)
    simulation.step();
  ASSERT_FALSE(simulation.metrics().events.empty()) << "no tear after 4 mm";
  // It tears from the slit (x = 0, |y| <= 0.8), not at the hand.
  const Vec2 from = simulation.metrics().events.front().event.from_rest;
  EXPECT_LT(std::abs(from.x()), 0.5) << from.transpose();
  EXPECT_LT(std::abs(from.y()), 1.0) << from.transpose();
}

} // namespace ligsim::membrane
