// Homogeneous uniaxial stretch of a cube against the closed-form answer for the same energy.
// Symmetry planes hold x = 0, y = 0, z = 0; the top face is moved to stretch lambda; the lateral
// faces are free. Linear and quadratic tets reproduce the homogeneous state exactly, so the
// reaction on the top face must equal A0 dW/dlambda at the lateral stretch m solving dW/dm = 0.

#include "sim/material/fiber_law.hpp"
#include "sim/material/volumetric_law.hpp"
#include "sim/mesh/node_selection.hpp"
#include "sim/mesh/quadratic_tet.hpp"
#include "sim/mesh/structured_mesh.hpp"
#include "sim/solver/static_solver.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <tuple>

using namespace ligsim::sim;

namespace {

/// W(lambda, m) for F = diag(m, m, lambda) and fibers along z with |a| = fiber_length, written
/// from the invariants of eq. 6 independently of the element code.
double energy_density(const MaterialParameters& p, double fiber_length, double lambda, double m)
{
  const double J = lambda * m * m;
  const double s = std::pow(J, -2.0 / 3.0);
  const double i1 = s * (2 * m * m + lambda * lambda);
  double w =
      0.5 * p.mu_mpa * (i1 - 3) + volumetric_response(p.volumetric, p.bulk_modulus_mpa, J).energy;
  if (p.fiber) {
    const double i4 = s * lambda * lambda * fiber_length * fiber_length;
    w += FiberLaw(*p.fiber).evaluate(std::sqrt(i4)).energy;
  }
  return w;
}

/// The 1-D lateral-stretch equation dW/dm = 0, by bisection on a central difference.
double lateral_stretch(const MaterialParameters& p, double fiber_length, double lambda)
{
  const double h = 1e-7;
  auto slope = [&](double m) {
    return (energy_density(p, fiber_length, lambda, m + h) -
            energy_density(p, fiber_length, lambda, m - h)) /
           (2 * h);
  };
  double low = 0.7;
  double high = 1.3;
  EXPECT_LT(slope(low), 0.0);
  EXPECT_GT(slope(high), 0.0);
  for (int k = 0; k < 200 && high - low > 1e-15; ++k) {
    const double middle = 0.5 * (low + high);
    (slope(middle) < 0.0 ? low : high) = middle;
  }
  return 0.5 * (low + high);
}

/// Nominal axial force on the unit cube's top face, N.
double closed_form_force(const MaterialParameters& p, double fiber_length, double lambda)
{
  const double m = lateral_stretch(p, fiber_length, lambda);
  const double h = 1e-6;
  return (energy_density(p, fiber_length, lambda + h, m) -
          energy_density(p, fiber_length, lambda - h, m)) /
         (2 * h);
}

struct Simulated {
  double force_n = 0.0;
  double lateral_stretch = 0.0;
};

/// The 2 x 2 x 2-hex cube, of linear tets or (`quadratic`) 10-node tets with the 4-point rule.
HyperelasticBody cube(const MaterialParameters& p, const FiberField& fiber, bool quadratic)
{
  const ligsim::TetMesh linear = structured_cube_mesh(2, 1.0);
  if (quadratic)
    return HyperelasticBody(promote_to_quadratic(linear), p, fiber, tet_quadrature(2));
  return HyperelasticBody(linear, p, fiber);
}

Simulated simulate(const MaterialParameters& p, double fiber_length, double lambda,
                   bool quadratic = false)
{
  ligsim::sim::FiberField fiber(1, 3);
  fiber << 0.0, 0.0, fiber_length;
  const HyperelasticBody body = cube(p, fiber, quadratic);
  const ligsim::TetMesh& mesh = body.mesh(); // every node, the mid-edge ones included
  BoundaryConditions conditions;
  for (int axis = 0; axis < 3; ++axis) {
    ConstraintSet plane;
    plane.name = std::string("symmetry_") + "xyz"[axis];
    plane.nodes = nodes_on_plane(mesh.V, axis, 0.0, 1e-9);
    plane.components = {axis == 0, axis == 1, axis == 2};
    conditions.constraints.push_back(plane);
  }
  ConstraintSet top;
  top.name = "top";
  top.nodes = nodes_on_plane(mesh.V, 2, 1.0, 1e-9);
  top.components = {false, false, true};
  top.displacement_mm = Eigen::Vector3d(0, 0, lambda - 1.0);
  conditions.constraints.push_back(top);
  NewtonSettings settings;
  settings.load_steps = 4;
  settings.residual_tolerance = 1e-12;
  StaticSolver solver(body, conditions, settings);
  Eigen::VectorXd x = body.rest_positions();
  Eigen::VectorXd residual;
  const StaticResult result = solver.solve(x, [&](const StepReport&, const Eigen::VectorXd&,
                                                  const Eigen::VectorXd& r) { residual = r; });
  EXPECT_TRUE(result.converged) << result.failure;
  Simulated out;
  out.force_n = reaction_forces(conditions, residual)[3].z();
  out.lateral_stretch = x(3 * 2); // node (2, 0, 0) sits at x = 1 in the rest shape
  return out;
}

using Case = std::tuple<double, FiberConvention, VolumetricLaw>;

class UniaxialStretch : public ::testing::TestWithParam<Case> {};

void expect_the_closed_form(const Case& c, bool quadratic)
{
  const auto [lambda, convention, volumetric] = c;
  MaterialParameters p = mcl_material();
  p.fiber->convention = convention;
  p.volumetric = volumetric;
  const double expected = closed_form_force(p, 1.0, lambda);
  const Simulated simulated = simulate(p, 1.0, lambda, quadratic);
  EXPECT_NEAR(simulated.force_n, expected, 1e-6 * std::abs(expected));
  EXPECT_NEAR(simulated.lateral_stretch, lateral_stretch(p, 1.0, lambda), 1e-8);
}

} // namespace

TEST_P(UniaxialStretch, ReactionMatchesClosedForm)
{
  expect_the_closed_form(GetParam(), false);
}

TEST_P(UniaxialStretch, QuadraticTetsMatchTheClosedFormToo)
{
  expect_the_closed_form(GetParam(), true);
}

INSTANTIATE_TEST_SUITE_P(
    RegimesConventionsVolumetric, UniaxialStretch,
    ::testing::Combine(::testing::Values(0.95, 1.02, 1.06),
                       ::testing::Values(FiberConvention::paper, FiberConvention::weiss),
                       ::testing::Values(VolumetricLaw::jm1, VolumetricLaw::lnj)),
    [](const ::testing::TestParamInfo<Case>& info) {
      const double lambda = std::get<0>(info.param);
      const std::string regime = lambda < 1 ? "compression" : lambda < 1.03 ? "toe" : "linear";
      return regime + "_" + to_string(std::get<1>(info.param)) + "_" +
             to_string(std::get<2>(info.param));
    });

TEST(UniaxialStretch, NeoHookeanWithoutFibers)
{
  MaterialParameters p;
  const double expected = closed_form_force(p, 1.0, 1.2);
  EXPECT_NEAR(simulate(p, 1.0, 1.2).force_n, expected, 1e-6 * std::abs(expected));
}

TEST(UniaxialStretch, InSituStrainPreStretchesTheFibers)
{
  // |a| = 1.029: the fibers are in their toe region before any deformation (sec. 2.7).
  const MaterialParameters p = mcl_material();
  const double expected = closed_form_force(p, 1.029, 1.01);
  EXPECT_NEAR(simulate(p, 1.029, 1.01).force_n, expected, 1e-6 * std::abs(expected));
  EXPECT_GT(expected, closed_form_force(p, 1.0, 1.01));
}
