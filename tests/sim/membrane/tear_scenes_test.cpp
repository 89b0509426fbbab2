/// The shipped tearing scenes, run to their end: the behaviour the paper shows, measured.

#include "sim/membrane/mesh/topology.hpp"
#include "sim/membrane/scene/scene.hpp"
#include "sim/membrane/scene/tear_metrics.hpp"
#include "sim/membrane/scene/tear_simulation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>

namespace ligsim::membrane {
namespace {

constexpr double kDegree = M_PI / 180.0;

std::filesystem::path scene_file(const std::string& name)
{
  return std::filesystem::path(LIGSIM_SOURCE_DIR) / "data" / "scenes" / (name + ".toml");
}

struct Outcome {
  TearMetrics metrics;
  double direction_deg = 0.0;
  RadiusStatistics radius;
  std::string manifold;
  int elements = 0;
};

Outcome run(const Scene& scene)
{
  TearSimulation simulation(scene);
  while (!simulation.finished())
    simulation.step();
  Outcome outcome;
  outcome.metrics = simulation.metrics();
  std::vector<TearEvent> events;
  for (const RecordedEvent& recorded : outcome.metrics.events)
    events.push_back(recorded.event);
  outcome.direction_deg = mean_tear_direction_deg(events);
  if (scene.run.centre_mm)
    outcome.radius = tear_radius(events, *scene.run.centre_mm);
  outcome.manifold = manifold_problem(simulation.mesh());
  outcome.elements = simulation.mesh().triangle_count();
  return outcome;
}

/// Each scene runs once for all the tests that look at it.
const Outcome& outcome_of(const std::string& name)
{
  static std::map<std::string, Outcome> cache;
  auto found = cache.find(name);
  if (found == cache.end())
    found = cache.emplace(name, run(load_scene(scene_file(name)))).first;
  return found->second;
}

void expect_sound_mesh(const Outcome& outcome)
{
  EXPECT_EQ(outcome.manifold, "");
  EXPECT_GE(outcome.metrics.min_angle_rad, 10.0 * kDegree - 1e-12);
  EXPECT_GT(outcome.metrics.face_splits, 0);
}

TEST(TearScenes, SquareSheetAt45DegreesTearsAlongTheFibers)
{
  const Outcome& sheet = outcome_of("square-sheet-45");
  EXPECT_NEAR(sheet.metrics.initial_elements, 1500, 50);
  EXPECT_TRUE(sheet.metrics.separated);
  EXPECT_GE(sheet.metrics.propagation_events, 20);
  EXPECT_NEAR(sheet.direction_deg, 45.0, 10.0);
  expect_sound_mesh(sheet);
}

TEST(TearScenes, SquareSheetsWithFibersAt0And90DegreesTearAcrossThePull)
{
  for (const char* name : {"square-sheet-0", "square-sheet-90"}) {
    const Outcome& sheet = outcome_of(name);
    EXPECT_TRUE(sheet.metrics.separated) << name;
    EXPECT_NEAR(sheet.direction_deg, 90.0, 10.0) << name;
    expect_sound_mesh(sheet);
  }
}

TEST(TearScenes, BreakingTheFibersNeedsSeveralTimesTheLoad)
{
  const Outcome& across = outcome_of("square-sheet-0"); // the tear must break the fibers
  const Outcome& along = outcome_of("square-sheet-90"); // the tear separates them
  ASSERT_TRUE(across.metrics.onset && along.metrics.onset);
  EXPECT_GE(across.metrics.onset->load_n / along.metrics.onset->load_n, 3.0);
}

TEST(TearScenes, CapsulorhexisTearFollowsACircle)
{
  const Outcome& eye = outcome_of("capsulorhexis");
  EXPECT_GE(std::abs(eye.metrics.turned_rad), M_PI) << "the tear ran less than a half turn";
  EXPECT_LT(eye.radius.coefficient_of_variation, 0.15);
  EXPECT_GT(eye.radius.mean_mm, 2.0);
  EXPECT_LT(eye.radius.mean_mm, 3.5);
  EXPECT_FALSE(eye.metrics.separated);
  expect_sound_mesh(eye);
}

TEST(TearScenes, AnIntactSheetTearsFromAnInitiation)
{
  // The 45-degree sheet without its slit: the tear must start at element centres.
  Scene scene = load_scene(scene_file("square-sheet-45"));
  scene.cuts.clear();
  scene.tearing.initiation = true;
  scene.tearing.initiation_clearance_mm = 1.0;
  const Outcome intact = run(scene);
  EXPECT_GE(intact.metrics.initiations, 1);
  EXPECT_TRUE(intact.metrics.separated);
  EXPECT_NEAR(intact.direction_deg, 45.0, 10.0);
  expect_sound_mesh(intact);
}

TEST(TearScenes, PrescribedVelocitiesDriveTheSides)
{
  // The 90-degree sheet pulled by moving its sides instead of loading them.
  Scene scene = load_scene(scene_file("square-sheet-90"));
  scene.tractions.clear();
  for (double side : {-1.0, 1.0}) {
    ConstraintSpec moving;
    moving.region.box_mm = Eigen::Vector4d(5.0 * side - 0.01, -5.01, 5.0 * side + 0.01, 5.01);
    moving.velocity_mm_per_s = Vec2(0.2 * side, 0.0);
    scene.fixed.push_back(moving);
  }
  TearSimulation simulation(scene);
  for (int step = 0; step < 100; ++step)
    simulation.step();
  const MembraneMesh& mesh = simulation.mesh();
  for (int v = 0; v < mesh.node_count(); ++v)
    if (std::abs(std::abs(mesh.rest[v].x()) - 5.0) < 1e-9) {
      const double expected = 0.2 * 0.1 * (mesh.rest[v].x() > 0.0 ? 1.0 : -1.0);
      ASSERT_NEAR(mesh.position[v].x() - mesh.rest[v].x(), expected, 1e-12) << v;
    }
  // Stretched along x: the mean sigma_x is tensile, below E_T times the 0.4 % imposed strain.
  double mean_sigma_x = 0.0;
  for (int tri = 0; tri < mesh.triangle_count(); ++tri)
    mean_sigma_x += simulation.elements().stress(tri)[0] / mesh.triangle_count();
  EXPECT_GT(mean_sigma_x, 0.0);
  EXPECT_LT(mean_sigma_x, 2.0 * 0.004 * 1.5);
}

TEST(TearScenes, AlongEdgesOnlyTheMeshIsNeverSplit)
{
  // Mode 1: the crack follows existing edges, so no element is created.
  Scene scene = load_scene(scene_file("square-sheet-90"));
  scene.tearing.propagation.split_faces = false;
  TearSimulation simulation(scene);
  const int elements = simulation.mesh().triangle_count();
  while (!simulation.finished())
    simulation.step();
  EXPECT_GT(simulation.metrics().propagation_events, 10);
  EXPECT_EQ(simulation.metrics().face_splits, 0);
  EXPECT_EQ(simulation.mesh().triangle_count(), elements);
  EXPECT_EQ(manifold_problem(simulation.mesh()), "");
}

} // namespace
} // namespace ligsim::membrane
