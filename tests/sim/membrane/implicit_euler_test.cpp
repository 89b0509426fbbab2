#include "sim/membrane/model/implicit_euler.hpp"

#include "tests/sim/membrane/test_material.hpp"

#include "common/error.hpp"
#include "sim/membrane/mesh/generate.hpp"
#include "sim/membrane/model/stiffness.hpp"

#include <Eigen/LU>
#include <gtest/gtest.h>

#include <cmath>

namespace ligsim::membrane {
namespace {

struct Sheet {
  MembraneMesh mesh;
  CorotationalElements elements;
};

Sheet pulled_sheet(double fiber_deg)
{
  Sheet sheet{rectangle_mesh(4.0, 2.0, 0.4, 0.15, 8),
              CorotationalElements(test::lens_like_material())};
  for (double& angle : sheet.mesh.fiber_angle_rad)
    angle = fiber_deg * M_PI / 180.0;
  sheet.elements.rebuild(sheet.mesh);
  std::vector<int> all(sheet.mesh.node_count());
  for (int v = 0; v < sheet.mesh.node_count(); ++v)
    all[v] = v;
  const MembraneMaterial m = test::lens_like_material();
  update_lumped_masses(sheet.mesh, build_incidence(sheet.mesh),
                       m.density_t_per_mm3 * m.thickness_mm, all);
  return sheet;
}

/// Nodal forces of a traction `per_length` (N/mm) outward on the sides x = +-2.
std::vector<Vec2> side_loads(const MembraneMesh& mesh, double per_length)
{
  std::vector<Vec2> forces(mesh.node_count(), Vec2::Zero());
  for (const Triangle& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const Vec2& a = mesh.rest[t[k]];
      const Vec2& b = mesh.rest[t[(k + 1) % 3]];
      for (double side : {-2.0, 2.0})
        if (std::abs(a.x() - side) < 1e-12 && std::abs(b.x() - side) < 1e-12) {
          const Vec2 half(0.5 * per_length * (b - a).norm() * (side > 0 ? 1.0 : -1.0), 0.0);
          forces[t[k]] += half;
          forces[t[(k + 1) % 3]] += half;
        }
    }
  return forces;
}

TEST(MembraneImplicitEuler, FreeSheetUnderOppositeTractionsSettlesToUniaxialStress)
{
  // Balanced tractions q on the sides of a free sheet: at rest every element carries
  // sigma_x = q / h and the sheet lengthens by S11 sigma_x per unit length, S = C(theta)^-1.
  const double per_length = 1e-4, fiber_deg = 30.0;
  Sheet sheet = pulled_sheet(fiber_deg);
  SolverSettings settings;
  settings.time_step_s = 1e-2;
  settings.mass_damping_per_s = 100.0;
  settings.cg_tolerance = 1e-10;
  settings.cg_max_iterations = 2000;
  ImplicitEuler euler(settings);
  const std::vector<Vec2> loads = side_loads(sheet.mesh, per_length);
  for (int step = 0; step < 150; ++step)
    euler.step(sheet.mesh, sheet.elements, loads);

  const MembraneMaterial m = test::lens_like_material();
  const double sigma = per_length / m.thickness_mm;
  for (int tri = 0; tri < sheet.mesh.triangle_count(); ++tri)
    ASSERT_LT((sheet.elements.stress(tri) - Eigen::Vector3d(sigma, 0.0, 0.0)).norm(), 2e-3 * sigma)
        << "element " << tri << " stress " << sheet.elements.stress(tri).transpose();

  const Eigen::Matrix3d compliance = rotated_stiffness(m, fiber_deg * M_PI / 180.0).inverse();
  double left = 0.0, right = 0.0;
  int left_count = 0, right_count = 0;
  for (int v = 0; v < sheet.mesh.node_count(); ++v) {
    const double u = sheet.mesh.position[v].x() - sheet.mesh.rest[v].x();
    if (sheet.mesh.rest[v].x() < -2.0 + 1e-12) {
      left += u;
      ++left_count;
    } else if (sheet.mesh.rest[v].x() > 2.0 - 1e-12) {
      right += u;
      ++right_count;
    }
  }
  const double elongation = right / right_count - left / left_count;
  EXPECT_NEAR(elongation, compliance(0, 0) * sigma * 4.0, 2e-3 * compliance(0, 0) * sigma * 4.0);
}

TEST(MembraneImplicitEuler, PrescribedNodesMoveWithTheirVelocity)
{
  Sheet sheet = pulled_sheet(0.0);
  for (int v = 0; v < sheet.mesh.node_count(); ++v)
    if (sheet.mesh.rest[v].x() < -2.0 + 1e-12) {
      sheet.mesh.constraint[v] = NodeConstraint::prescribed;
      sheet.mesh.prescribed_velocity[v] = Vec2(0.0, 0.5);
    }
  SolverSettings settings;
  settings.mass_damping_per_s = 10.0;
  ImplicitEuler euler(settings);
  const std::vector<Vec2> none(sheet.mesh.node_count(), Vec2::Zero());
  for (int step = 0; step < 20; ++step)
    euler.step(sheet.mesh, sheet.elements, none);
  for (int v = 0; v < sheet.mesh.node_count(); ++v) {
    if (sheet.mesh.constraint[v] == NodeConstraint::prescribed) {
      ASSERT_LT((sheet.mesh.position[v] - sheet.mesh.rest[v] - Vec2(0.0, 0.5 * 20 * 1e-3)).norm(),
                1e-12);
    }
  }
}

TEST(MembraneImplicitEuler, RejectsBadSettings)
{
  SolverSettings settings;
  settings.time_step_s = 0.0;
  EXPECT_THROW(validate(settings, "scene"), InputError);
  settings = SolverSettings();
  settings.mass_damping_per_s = -1.0;
  EXPECT_THROW(validate(settings, "scene"), InputError);
  settings = SolverSettings();
  settings.cg_max_iterations = 0;
  EXPECT_THROW(validate(settings, "scene"), InputError);
}

} // namespace
} // namespace ligsim::membrane
