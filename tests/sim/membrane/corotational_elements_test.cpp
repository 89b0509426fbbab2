#include "sim/membrane/model/corotational_elements.hpp"

#include "tests/sim/membrane/test_material.hpp"

#include "sim/membrane/mesh/generate.hpp"
#include "sim/membrane/model/stiffness.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace ligsim::membrane {
namespace {

MembraneMesh sheet(double fiber_deg)
{
  MembraneMesh mesh = rectangle_mesh(3.0, 2.0, 0.5, 0.15, 4);
  for (double& angle : mesh.fiber_angle_rad)
    angle = fiber_deg * M_PI / 180.0;
  return mesh;
}

std::vector<Vec2> forces_at(const MembraneMesh& mesh, CorotationalElements& elements)
{
  std::vector<Vec2> forces(mesh.node_count(), Vec2::Zero());
  elements.add_forces(mesh, forces);
  return forces;
}

double max_norm(const std::vector<Vec2>& values)
{
  double largest = 0.0;
  for (const Vec2& v : values)
    largest = std::max(largest, v.norm());
  return largest;
}

TEST(CorotationalElements, RigidMotionsMakeNoForceAndNoStress)
{
  MembraneMesh mesh = sheet(30.0);
  CorotationalElements elements(test::lens_like_material());
  elements.rebuild(mesh);
  for (double degrees : {0.0, 37.0, 90.0, 170.0, -120.0}) {
    const Eigen::Rotation2Dd rotation(degrees * M_PI / 180.0);
    for (int v = 0; v < mesh.node_count(); ++v)
      mesh.position[v] = rotation * mesh.rest[v] + Vec2(4.0, -7.0);
    EXPECT_LT(max_norm(forces_at(mesh, elements)), 1e-12) << degrees;
    for (int tri = 0; tri < mesh.triangle_count(); ++tri)
      ASSERT_LT(elements.stress(tri).norm(), 1e-12);
  }
}

TEST(CorotationalElements, UniformStretchGivesTheMaterialStressInEveryElementAnyRotation)
{
  const MembraneMaterial m = test::lens_like_material();
  MembraneMesh mesh = sheet(30.0);
  CorotationalElements elements(m);
  elements.rebuild(mesh);
  // A small symmetric stretch U, then a large rotation: the stress is C eps in the rest frame.
  Eigen::Matrix2d stretch;
  stretch << 1.002, 0.0005, 0.0005, 0.999;
  const Eigen::Vector3d strain(0.002, -0.001, 0.001); // eps_x, eps_y, gamma_xy = 2 eps_xy
  const Eigen::Vector3d expected = rotated_stiffness(m, 30.0 * M_PI / 180.0) * strain;
  for (double degrees : {0.0, 65.0, -150.0}) {
    const Eigen::Matrix2d deformation =
        Eigen::Rotation2Dd(degrees * M_PI / 180.0).toRotationMatrix() * stretch;
    for (int v = 0; v < mesh.node_count(); ++v)
      mesh.position[v] = deformation * mesh.rest[v];
    forces_at(mesh, elements);
    for (int tri = 0; tri < mesh.triangle_count(); ++tri)
      ASSERT_LT((elements.stress(tri) - expected).norm(), 1e-6 * expected.norm()) << tri;
  }
}

TEST(CorotationalElements, InteriorNodesAreInEquilibriumUnderUniformStress)
{
  // The patch test: under a uniform strain the internal forces cancel at interior nodes.
  MembraneMesh mesh = sheet(45.0);
  CorotationalElements elements(test::lens_like_material());
  elements.rebuild(mesh);
  Eigen::Matrix2d stretch;
  stretch << 1.01, 0.002, 0.0, 0.995;
  for (int v = 0; v < mesh.node_count(); ++v)
    mesh.position[v] = stretch * mesh.rest[v];
  const std::vector<Vec2> forces = forces_at(mesh, elements);
  double boundary_force = 0.0;
  for (int v = 0; v < mesh.node_count(); ++v) {
    const Vec2& p = mesh.rest[v];
    const bool boundary =
        std::abs(std::abs(p.x()) - 1.5) < 1e-9 || std::abs(std::abs(p.y()) - 1.0) < 1e-9;
    if (boundary)
      boundary_force = std::max(boundary_force, forces[v].norm());
    else
      EXPECT_LT(forces[v].norm(), 1e-6 * boundary_force + 1e-14) << v;
  }
  EXPECT_GT(boundary_force, 0.0);
}

TEST(CorotationalElements, TangentMatchesFiniteDifferencesOfTheForces)
{
  // At a rigidly rotated rest state dR/dx does not contribute (the stress is zero), so the
  // tangent R K_e R^T is the exact derivative of the forces.
  MembraneMesh mesh = sheet(60.0);
  CorotationalElements elements(test::lens_like_material());
  elements.rebuild(mesh);
  const Eigen::Rotation2Dd rotation(0.7);
  for (int v = 0; v < mesh.node_count(); ++v)
    mesh.position[v] = rotation * mesh.rest[v];
  std::mt19937 random(9);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<Vec2> direction(mesh.node_count());
  for (Vec2& d : direction)
    d = Vec2(unit(random), unit(random));
  forces_at(mesh, elements);
  std::vector<Vec2> tangent(mesh.node_count(), Vec2::Zero());
  elements.add_stiffness_times(mesh, direction, tangent);

  const double h = 1e-6;
  const MembraneMesh base = mesh;
  for (int v = 0; v < mesh.node_count(); ++v)
    mesh.position[v] = base.position[v] + h * direction[v];
  const std::vector<Vec2> plus = forces_at(mesh, elements);
  for (int v = 0; v < mesh.node_count(); ++v)
    mesh.position[v] = base.position[v] - h * direction[v];
  const std::vector<Vec2> minus = forces_at(mesh, elements);
  double error = 0.0, scale = 0.0;
  for (int v = 0; v < mesh.node_count(); ++v) {
    const Vec2 derivative = -(plus[v] - minus[v]) / (2.0 * h); // K = -df/dx
    error = std::max(error, (derivative - tangent[v]).norm());
    scale = std::max(scale, tangent[v].norm());
  }
  EXPECT_LT(error, 1e-6 * scale);
}

TEST(CorotationalElements, TangentIsSymmetricAndItsDiagonalIsRight)
{
  MembraneMesh mesh = sheet(20.0);
  CorotationalElements elements(test::lens_like_material());
  elements.rebuild(mesh);
  Eigen::Matrix2d deformation;
  deformation << 0.9, -0.5, 0.45, 0.95;
  for (int v = 0; v < mesh.node_count(); ++v)
    mesh.position[v] = deformation * mesh.rest[v];
  forces_at(mesh, elements);
  std::mt19937 random(4);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<Vec2> p(mesh.node_count()), q(mesh.node_count());
  for (int v = 0; v < mesh.node_count(); ++v) {
    p[v] = Vec2(unit(random), unit(random));
    q[v] = Vec2(unit(random), unit(random));
  }
  std::vector<Vec2> kp(mesh.node_count(), Vec2::Zero()), kq(mesh.node_count(), Vec2::Zero());
  elements.add_stiffness_times(mesh, p, kp);
  elements.add_stiffness_times(mesh, q, kq);
  double pkq = 0.0, qkp = 0.0;
  for (int v = 0; v < mesh.node_count(); ++v) {
    pkq += p[v].dot(kq[v]);
    qkp += q[v].dot(kp[v]);
  }
  EXPECT_NEAR(pkq, qkp, 1e-12 * std::abs(pkq));

  std::vector<Vec2> diagonal(mesh.node_count(), Vec2::Zero());
  elements.add_stiffness_diagonal(mesh, diagonal);
  for (int v : {0, 7, 20}) {
    for (int axis = 0; axis < 2; ++axis) {
      std::vector<Vec2> e(mesh.node_count(), Vec2::Zero()), ke(mesh.node_count(), Vec2::Zero());
      e[v][axis] = 1.0;
      elements.add_stiffness_times(mesh, e, ke);
      EXPECT_NEAR(diagonal[v][axis], ke[v][axis], 1e-12 * std::abs(ke[v][axis]));
    }
  }
}

} // namespace
} // namespace ligsim::membrane
