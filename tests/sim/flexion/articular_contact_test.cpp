/// The elastic-foundation articular contact on a sphere (the femur's condyle) pressed into a
/// plane (the tibia): the force of the foundation's closed form, and exact derivatives in the
/// femur's five free coordinates against central differences.

#include "sim/flexion/articular_contact.hpp"
#include "sim/mesh/sphere_surface.hpp"

#include <gtest/gtest.h>

using namespace ligsim::sim;

namespace {

JointCoordinateSystem knee()
{
  JointCoordinateSystem jcs;
  jcs.origin_mm = Eigen::Vector3d(0.0, 0.0, 20.0);
  jcs.flexion_axis = Eigen::Vector3d::UnitX();
  jcs.tibial_axis = Eigen::Vector3d::UnitZ();
  jcs.side = +1;
  return jcs;
}

} // namespace

TEST(ArticularContact, ASpherePressedIntoAPlaneGivesTheFoundationsForce)
{
  // A 20 mm condyle whose lowest point lies 0.3 mm into the tibia's plane z = 0.
  const double radius = 20.0, depth = 0.3;
  const ligsim::TriangleSurface condyle =
      sphere_surface(Eigen::Vector3d(0.0, 0.0, radius - depth), radius, 6);
  const PlaneDistance tibia(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ());
  ArticularSettings settings;
  const ArticularContact contact(condyle, tibia, knee(), settings);
  const ArticularState state = contact.evaluate(FreePose(knee(), 0.0, Vector5d::Zero()));
  // The foundation under a paraboloid: F = (K / h) pi R delta^2. Measured: 0.4 % under (the
  // sphere's chords).
  const double expected = contact.stiffness() * M_PI * radius * depth * depth;
  const Eigen::Vector3d total = state.medial_force_n + state.lateral_force_n;
  EXPECT_NEAR(total.z(), expected, 0.02 * expected);
  EXPECT_NEAR(total.head<2>().norm(), 0.0, 1e-6 * expected);
  // Symmetric about the flexion axis' plane: half medial, half lateral, centres on the plane.
  EXPECT_NEAR(state.medial_force_n.z(), state.lateral_force_n.z(), 0.05 * expected);
  EXPECT_NEAR(state.medial_centre_mm.z(), 0.0, 1e-9);
  EXPECT_LT(state.medial_centre_mm.x(), 0.0);
  EXPECT_GT(state.lateral_centre_mm.x(), 0.0);
}

TEST(ArticularContact, ItsDerivativesInTheFreeCoordinatesAreExact)
{
  const ligsim::TriangleSurface condyle = sphere_surface(Eigen::Vector3d(3.0, -2.0, 19.0), 20.0, 5);
  const PlaneDistance tibia(Eigen::Vector3d(0.0, 0.0, 0.2),
                            Eigen::Vector3d(0.05, 0.1, 1.0).normalized());
  const ArticularContact contact(condyle, tibia, knee(), ArticularSettings{});
  Vector5d q;
  q << 0.02, -0.05, 0.4, -0.6, 0.25;
  const double flexion = 35.0;
  const ArticularState at = contact.evaluate(FreePose(knee(), flexion, q));
  ASSERT_GT(at.energy_nmm, 0.0);
  const double h = 1e-6;
  for (int k = 0; k < 5; ++k) {
    Vector5d plus = q, minus = q;
    plus(k) += h;
    minus(k) -= h;
    const ArticularState p = contact.evaluate(FreePose(knee(), flexion, plus));
    const ArticularState m = contact.evaluate(FreePose(knee(), flexion, minus));
    const double gradient = (p.energy_nmm - m.energy_nmm) / (2.0 * h);
    EXPECT_NEAR(at.gradient(k), gradient, 1e-5 * at.gradient.norm()) << k;
    const Vector5d column = (p.gradient - m.gradient) / (2.0 * h);
    EXPECT_LT((at.hessian.col(k) - column).norm(), 1e-4 * at.hessian.norm()) << k;
  }
}
