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

TEST(ArticularContact, ASeatedKneeMeetsInBothCompartmentsWhereItWasBuilt)
{
  // Two 15 mm condyles over the tibia's plane z = 0: the medial one (x < 0) 1 mm above it, the
  // lateral one 3 mm above, as an atlas without tibial cartilage and menisci leaves them.
  const double radius = 15.0;
  const ligsim::TriangleSurface medial =
      sphere_surface(Eigen::Vector3d(-20.0, 0.0, radius + 1.0), radius, 6);
  const ligsim::TriangleSurface lateral =
      sphere_surface(Eigen::Vector3d(20.0, 0.0, radius + 3.0), radius, 6);
  ligsim::TriangleSurface condyles;
  condyles.V.resize(medial.V.rows() + lateral.V.rows(), 3);
  condyles.V << medial.V, lateral.V;
  condyles.F.resize(medial.F.rows() + lateral.F.rows(), 3);
  condyles.F << medial.F, lateral.F.array() + static_cast<int>(medial.V.rows());
  const PlaneDistance tibia(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ());

  ArticularSettings settings;
  const ArticularContact seated(condyles, tibia, knee(), settings);
  // Each compartment meets where it stood (the lowest triangle's centroid sits a chord's sag
  // above the sphere's bottom).
  EXPECT_NEAR(seated.seat().medial_built_mm, 1.0, 0.1);
  EXPECT_NEAR(seated.seat().lateral_built_mm, 3.0, 0.1);
  EXPECT_EQ(seated.seat().medial_gap_mm, seated.seat().medial_built_mm);
  EXPECT_EQ(seated.seat().lateral_gap_mm, seated.seat().lateral_built_mm);
  EXPECT_EQ(seated.evaluate(FreePose(knee(), 0.0, Vector5d::Zero())).energy_nmm, 0.0);
  // The femur 0.4 mm down the tibial axis: both compartments carry the foundation's force.
  Vector5d down = Vector5d::Zero();
  down(4) = 0.4;
  const ArticularState pressed = seated.evaluate(FreePose(knee(), 0.0, down));
  const double expected = seated.stiffness() * M_PI * radius * 0.4 * 0.4;
  EXPECT_NEAR(pressed.medial_force_n.z(), expected, 0.05 * expected);
  EXPECT_NEAR(pressed.lateral_force_n.z(), expected, 0.05 * expected);

  // Not seated: the same pose leaves both condyles off the plane.
  settings.seated = false;
  const ArticularContact as_given(condyles, tibia, knee(), settings);
  EXPECT_EQ(as_given.seat().medial_gap_mm, 0.0);
  EXPECT_EQ(as_given.evaluate(FreePose(knee(), 0.0, down)).energy_nmm, 0.0);
  // A stated gap larger than the built separation is kept; a compartment farther apart than
  // kMaxSeatMm is not seated.
  settings.seated = true;
  settings.gap_mm = 2.0;
  const ArticularContact wider(condyles, tibia, knee(), settings);
  EXPECT_EQ(wider.seat().medial_gap_mm, 2.0);
  EXPECT_EQ(wider.seat().lateral_gap_mm, wider.seat().lateral_built_mm);
  const ligsim::TriangleSurface far =
      sphere_surface(Eigen::Vector3d(20.0, 0.0, radius + kMaxSeatMm + 1.0), radius, 6);
  const ArticularContact lifted(far, tibia, knee(), ArticularSettings{});
  EXPECT_EQ(lifted.seat().lateral_gap_mm, 0.0);
}
