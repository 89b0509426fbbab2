#include "common/error.hpp"
#include "sim/contact/barrier.hpp"
#include "sim/contact/bone_level_set.hpp"
#include "sim/contact/contact_potential.hpp"

#include "sim/mesh/sphere_surface.hpp"

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include <random>

using namespace ligsim::sim;

namespace {

/// A turning and shifting obstacle motion, so that the pose enters every derivative.
RigidMotion turning()
{
  RigidMotion motion;
  motion.axis = Eigen::Vector3d(0.3, 1.0, 0.2).normalized();
  motion.point_mm = Eigen::Vector3d(0.5, -0.2, 0.1);
  motion.angle_rad = 0.7;
  motion.translation_mm = Eigen::Vector3d(0.1, 0.0, -0.05);
  return motion;
}

/// Nodes 0..n-1 scattered within `d_hat` of the obstacle's surface (posed at load factor t).
Eigen::VectorXd near_surface(const ContactPotential& contact, int n, double t, unsigned seed)
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Eigen::VectorXd x(3 * n);
  const double d_hat = contact.settings().d_hat_mm;
  for (int i = 0; i < n;) {
    const Eigen::Vector3d p(4.0 * unit(random), 4.0 * unit(random), 4.0 * unit(random));
    const double d = contact.distance(0, p, t);
    if (d > 0.05 * d_hat && d < 0.95 * d_hat)
      x.segment<3>(3 * i++) = p;
  }
  return x;
}

ContactSurface two_nodes()
{
  ContactSurface surface;
  surface.nodes = {0, 1};
  surface.areas_mm2 = Eigen::Vector2d(1.0, 1.0);
  return surface;
}

void expect_exact_derivatives(const DistanceField& field, double tolerance)
{
  const int n = 12;
  std::vector<int> nodes(n);
  for (int i = 0; i < n; ++i)
    nodes[static_cast<std::size_t>(i)] = i;
  ContactObstacle obstacle{"obstacle", &field, turning(), {}};
  ContactSettings settings;
  settings.d_hat_mm = 0.5;
  settings.stiffness_mpa_per_mm = 7.0;
  ContactSurface surface;
  surface.nodes = nodes;
  surface.areas_mm2 = Eigen::VectorXd::LinSpaced(n, 0.5, 1.5);
  const ContactPotential contact(n, surface, {obstacle}, settings);
  const double t = 0.4;
  const Eigen::VectorXd x = near_surface(contact, n, t, 3);
  Eigen::VectorXd gradient = Eigen::VectorXd::Zero(3 * n);
  ASSERT_TRUE(std::isfinite(contact.energy(x, t, &gradient)));
  std::vector<NodeBlock> blocks;
  contact.hessian_blocks(x, t, false, blocks);
  ASSERT_EQ(blocks.size(), static_cast<std::size_t>(n));
  const double h = 1e-6;
  for (const NodeBlock& block : blocks) {
    for (int a = 0; a < 3; ++a) {
      Eigen::VectorXd plus = x, minus = x;
      plus(3 * block.node + a) += h;
      minus(3 * block.node + a) -= h;
      Eigen::VectorXd g_plus = Eigen::VectorXd::Zero(3 * n), g_minus = g_plus;
      const double e_plus = contact.energy(plus, t, &g_plus);
      const double e_minus = contact.energy(minus, t, &g_minus);
      const double g = gradient(3 * block.node + a);
      EXPECT_NEAR(g, (e_plus - e_minus) / (2 * h), tolerance * (std::abs(g) + 1e-3));
      const Eigen::Vector3d column = (g_plus - g_minus).segment<3>(3 * block.node) / (2 * h);
      EXPECT_LT((block.block.col(a) - column).norm(), tolerance * (block.block.norm() + 1e-3))
          << "node " << block.node << " column " << a;
    }
  }
  // The solvers' blocks are the projections: symmetric positive semi-definite.
  std::vector<NodeBlock> projected;
  contact.hessian_blocks(x, t, true, projected);
  for (const NodeBlock& block : projected) {
    EXPECT_LT((block.block - block.block.transpose()).norm(), 1e-12 * block.block.norm());
    EXPECT_GE(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(block.block).eigenvalues().minCoeff(),
              -1e-9 * block.block.norm());
  }
}

} // namespace

TEST(ContactPotential, ExactGradientAndHessianOnACylinder)
{
  const CylinderDistance cylinder({0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, 2.0);
  expect_exact_derivatives(cylinder, 1e-5);
}

TEST(ContactPotential, ExactGradientAndHessianOnALevelSet)
{
  const BoneLevelSet sphere(sphere_surface({0.2, 0.1, -0.3}, 2.5, 4), {0.2, 1.0});
  expect_exact_derivatives(sphere, 1e-5);
}

TEST(ContactPotential, CullingChangesNoEnergyGradientOrHessian)
{
  // Nodes from inside d_hat to beyond the band, d_hat close to the band (where the cull's slack
  // must shrink to fit it), moved in small steps as a sweep moves them: the potential equals the
  // barrier summed over every node from a fresh sample (to round-off: the test poses the nodes
  // its own way).
  const BoneLevelSet sphere(sphere_surface({0.2, 0.1, -0.3}, 2.5, 4), {0.2, 1.0});
  ContactSettings settings;
  settings.d_hat_mm = 0.8;
  settings.stiffness_mpa_per_mm = 7.0;
  const int n = 400;
  ContactSurface surface;
  for (int i = 0; i < n; ++i)
    surface.nodes.push_back(i);
  surface.areas_mm2 = Eigen::VectorXd::LinSpaced(n, 0.5, 1.5);
  const RigidMotion motion = turning();
  const ContactPotential contact(n, surface, {{"sphere", &sphere, motion, {}}}, settings);
  std::mt19937 random(5);
  std::uniform_real_distribution<double> gap(0.3, 2.5);
  Eigen::VectorXd x(3 * n);
  const double t0 = 0.3;
  const Eigen::Isometry3d pose = motion.pose(t0);
  for (int i = 0; i < n; ++i)
    x.segment<3>(3 * i) = pose * (Eigen::Vector3d(0.2, 0.1, -0.3) +
                                  (2.5 + gap(random)) * Eigen::Vector3d::Random().normalized());
  const Eigen::VectorXd drift = 0.005 * Eigen::VectorXd::Random(3 * n);
  int touching = 0;
  for (int step = 0; step < 30; ++step) {
    const double t = t0 + 0.001 * step;
    x += drift;
    Eigen::VectorXd gradient = Eigen::VectorXd::Zero(3 * n);
    const double energy = contact.energy(x, t, &gradient);
    std::vector<NodeBlock> blocks;
    contact.hessian_blocks(x, t, false, blocks);
    double expected = 0.0;
    Eigen::VectorXd expected_gradient = Eigen::VectorXd::Zero(3 * n);
    std::vector<NodeBlock> expected_blocks;
    const Eigen::Isometry3d at = motion.pose(t);
    const Eigen::Matrix3d rotation = at.linear();
    for (int i = 0; i < n; ++i) {
      const DistanceSample s =
          sphere.sample(at.inverse() * Eigen::Vector3d(x.segment<3>(3 * i)), true);
      const BarrierValue b = ipc_barrier(s.distance_mm, settings.d_hat_mm);
      const double area = surface.areas_mm2(i);
      expected += settings.stiffness_mpa_per_mm * area * b.value;
      if (b.first == 0.0 && b.second == 0.0)
        continue;
      const Eigen::Vector3d g = rotation * s.gradient;
      expected_gradient.segment<3>(3 * i) = settings.stiffness_mpa_per_mm * area * b.first * g;
      expected_blocks.push_back({i, settings.stiffness_mpa_per_mm * area *
                                        (b.second * g * g.transpose() +
                                         b.first * (rotation * s.hessian * rotation.transpose()))});
    }
    EXPECT_NEAR(energy, expected, 1e-12 * std::abs(expected));
    EXPECT_LE((gradient - expected_gradient).norm(), 1e-12 * expected_gradient.norm());
    ASSERT_EQ(blocks.size(), expected_blocks.size()) << "step " << step;
    double largest = 0.0;
    for (const NodeBlock& block : expected_blocks)
      largest = std::max(largest, block.block.norm());
    for (std::size_t k = 0; k < blocks.size(); ++k) {
      EXPECT_EQ(blocks[k].node, expected_blocks[k].node);
      EXPECT_LE((blocks[k].block - expected_blocks[k].block).norm(), 1e-12 * largest);
    }
    touching += static_cast<int>(blocks.size());
  }
  EXPECT_GT(touching, 30 * n / 10); // the case has nodes within d_hat
}

TEST(ContactPotential, ADHatBeyondTheGridsBandIsAnError)
{
  const BoneLevelSet sphere(sphere_surface({0.0, 0.0, 0.0}, 2.5, 3), {0.2, 1.0});
  ContactSettings settings;
  settings.d_hat_mm = 1.5;
  EXPECT_THROW(ContactPotential(2, two_nodes(), {{"sphere", &sphere, std::nullopt, {}}}, settings),
               ligsim::InputError);
}

TEST(ContactPotential, StepBoundStopsShortOfTheSurface)
{
  const PlaneDistance plane({0.0, 0.0, 0.0}, {0.0, 0.0, 1.0});
  ContactSettings settings;
  const ContactPotential contact(2, two_nodes(), {{"plane", &plane, std::nullopt, {}}}, settings);
  Eigen::VectorXd x(6);
  x << 0, 0, 0.2, 5, 0, 3.0;
  Eigen::VectorXd dx(6);
  dx << 1, 0, -1.0, 0, 0, -1.0; // the first node would end 0.8 mm below the plane
  const double alpha = contact.max_step(x, dx, 0.0);
  EXPECT_GT(alpha, 0.0);
  EXPECT_LE(0.2 - alpha * 1.0, 0.2);
  EXPECT_GE(0.2 - alpha * 1.0, 0.2 * 0.2 - 1e-12); // closes at most 80 % of the gap
  EXPECT_GT(0.2 - alpha * 1.0, 0.0);
  dx(2) = 0.05;
  EXPECT_EQ(contact.max_step(x, dx, 0.0), 1.0); // moving away: no bound
}

TEST(ContactPotential, NodesInsideAMovedObstacleArePushedOut)
{
  const PlaneDistance plane({0.0, 0.0, 0.0}, {0.0, 0.0, 1.0});
  RigidMotion lift;
  lift.translation_mm = Eigen::Vector3d(0.0, 0.0, 1.0);
  ContactSettings settings;
  const ContactPotential contact(2, two_nodes(), {{"plane", &plane, lift, {1}}}, settings);
  Eigen::VectorXd x(6);
  x << 0, 0, 0.5, 0, 0, 0.5; // the plane rises to z = 1 at t = 1: both inside
  EXPECT_TRUE(std::isinf(contact.energy(x, 1.0, nullptr)));
  EXPECT_EQ(contact.make_admissible(x, 1.0), 1); // node 1 is bound to the plane
  EXPECT_NEAR(x(2), 1.0 + 0.1 * settings.d_hat_mm, 1e-12);
  EXPECT_EQ(x(5), 0.5);
  EXPECT_TRUE(std::isfinite(contact.energy(x, 1.0, nullptr)));
}
