#include "sim/contact/bone_level_set.hpp"
#include "sim/contact/contact_potential.hpp"
#include "sim/contact/contact_surface.hpp"
#include "sim/mesh/node_selection.hpp"
#include "sim/mesh/structured_mesh.hpp"
#include "sim/solver/implicit_euler.hpp"
#include "sim/solver/static_solver.hpp"

#include "tests/sim/contact/cylinder_surface.hpp"
#include "tests/sim/solver/cube_tension.hpp"

#include <gtest/gtest.h>

using namespace ligsim::sim;

namespace {

FiberField no_fibers()
{
  return FiberField(0, 3);
}

/// The MCL's ground substance alone (Neo-Hookean, mu 27.7 MPa, K 1000 MPa).
MaterialParameters ground_substance()
{
  MaterialParameters material = mcl_material();
  material.fiber.reset();
  return material;
}

/// Contact of every free boundary node of `mesh` with `obstacles`.
ContactPotential boundary_contact(const ligsim::TetMesh& mesh, const BoundaryConditions& conditions,
                                  std::vector<ContactObstacle> obstacles,
                                  const ContactSettings& settings)
{
  return ContactPotential(static_cast<int>(mesh.V.rows()), free_boundary_surface(mesh, conditions),
                          std::move(obstacles), settings);
}

/// A quarter block on symmetry planes x = 0 and y = 0, pushed down by `total_n` spread over
/// its top face at z = `top_z_mm`.
BoundaryConditions quarter_block_pushed_down(const ligsim::TetMesh& mesh, double top_z_mm,
                                             double total_n)
{
  BoundaryConditions conditions;
  ConstraintSet x_symmetry{"x0",
                           nodes_on_plane(mesh.V, 0, 0.0, 1e-9),
                           {true, false, false},
                           Eigen::Vector3d::Zero(),
                           std::nullopt};
  ConstraintSet y_symmetry{"y0",
                           nodes_on_plane(mesh.V, 1, 0.0, 1e-9),
                           {false, true, false},
                           Eigen::Vector3d::Zero(),
                           std::nullopt};
  conditions.constraints = {x_symmetry, y_symmetry};
  NodalLoad load{"top", nodes_on_plane(mesh.V, 2, top_z_mm, 1e-9), Eigen::Vector3d::Zero()};
  load.force_per_node_n = Eigen::Vector3d(0, 0, -total_n / static_cast<double>(load.nodes.size()));
  conditions.loads = {load};
  return conditions;
}

} // namespace

TEST(ContactSolvers, ContactThatNeverTouchesChangesNothingBitForBit)
{
  const ligsim::TetMesh mesh = structured_cube_mesh(3, 1.0);
  FiberField fiber(1, 3);
  fiber << 0, 0, 1;
  const HyperelasticBody body(mesh, mcl_material(), fiber);
  const BoundaryConditions conditions = test::cube_tension(mesh, {0.01, 0.0, 0.1});
  const PlaneDistance far_plane({0.0, 0.0, -5.0}, {0.0, 0.0, 1.0});
  const ContactPotential contact =
      boundary_contact(mesh, conditions, {{"plane", &far_plane, std::nullopt, {}}}, {});

  NewtonSettings newton;
  newton.load_steps = 3;
  Eigen::VectorXd without = body.rest_positions();
  Eigen::VectorXd with = without;
  StaticSolver plain(body, conditions, newton);
  StaticSolver contacting(body, conditions, newton);
  contacting.set_extra_potential(&contact);
  ASSERT_TRUE(plain.solve(without).converged);
  ASSERT_TRUE(contacting.solve(with).converged);
  EXPECT_EQ((with - without).lpNorm<Eigen::Infinity>(), 0.0);

  DynamicsSettings dynamics;
  dynamics.frames = 5;
  dynamics.linear_solver = LinearSolverKind::direct;
  without = body.rest_positions();
  with = without;
  ImplicitEuler plain_euler(body, conditions, dynamics);
  ImplicitEuler contacting_euler(body, conditions, dynamics);
  contacting_euler.set_extra_potential(&contact);
  ASSERT_TRUE(plain_euler.run(without).completed);
  ASSERT_TRUE(contacting_euler.run(with).completed);
  EXPECT_EQ((with - without).lpNorm<Eigen::Infinity>(), 0.0);
}

TEST(ContactSolvers, BlockPressedOnAPlaneFeelsTheLoadAsReaction)
{
  ligsim::TetMesh mesh = structured_box_mesh({4, 4, 2}, {2.0, 2.0, 1.0});
  mesh.V.col(2).array() += 0.2; // 0.2 mm above the plane z = 0
  const HyperelasticBody body(mesh, ground_substance(), no_fibers());
  const double total_n = 20.0; // 5 MPa on 4 mm^2
  const BoundaryConditions conditions = quarter_block_pushed_down(mesh, 1.2, total_n);
  const PlaneDistance plane({0.0, 0.0, 0.0}, {0.0, 0.0, 1.0});
  ContactSettings settings;
  settings.d_hat_mm = 0.3;
  const ContactPotential contact =
      boundary_contact(mesh, conditions, {{"plane", &plane, std::nullopt, {}}}, settings);

  NewtonSettings newton;
  newton.load_steps = 4;
  newton.residual_tolerance = 1e-11;
  StaticSolver solver(body, conditions, newton);
  solver.set_extra_potential(&contact);
  Eigen::VectorXd x = body.rest_positions();
  const StaticResult result = solver.solve(x);
  ASSERT_TRUE(result.converged) << result.failure;
  const ContactMeasures measures = contact.measure(x, 1.0);
  EXPECT_NEAR(measures.force_n[0].z(), total_n, 1e-9 * total_n);
  EXPECT_LT(measures.force_n[0].head<2>().norm(), 1e-9 * total_n);
  EXPECT_GT(measures.min_gap_mm[0], 0.0);
  EXPECT_LT(measures.min_gap_mm[0], settings.d_hat_mm);
  // The whole bottom face touches, widened by the compression: its deformed area.
  const ligsim::Triangles faces = boundary_surface(mesh).faces;
  double bottom_area = 0.0;
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    if (mesh.V(faces(f, 0), 2) + mesh.V(faces(f, 1), 2) + mesh.V(faces(f, 2), 2) < 0.61) {
      const Eigen::Vector3d a = x.segment<3>(3 * faces(f, 0));
      bottom_area +=
          0.5 * (x.segment<3>(3 * faces(f, 1)) - a).cross(x.segment<3>(3 * faces(f, 2)) - a).norm();
    }
  EXPECT_GT(bottom_area, 4.0);
  EXPECT_NEAR(measures.area_mm2[0], bottom_area, 1e-12);
}

TEST(ContactSolvers, ImplicitEulerFramesNeverCrossThePlaneAndComeToRestOnIt)
{
  ligsim::TetMesh mesh = structured_box_mesh({4, 4, 2}, {2.0, 2.0, 1.0});
  mesh.V.col(2).array() += 1.0; // beyond d_hat: nothing resists the first frame's fall
  const HyperelasticBody body(mesh, ground_substance(), no_fibers());
  const double total_n = 100.0;
  const BoundaryConditions conditions = quarter_block_pushed_down(mesh, 2.0, total_n);
  const PlaneDistance plane({0.0, 0.0, 0.0}, {0.0, 0.0, 1.0});
  ContactSettings settings;
  settings.d_hat_mm = 0.3;
  const ContactPotential contact =
      boundary_contact(mesh, conditions, {{"plane", &plane, std::nullopt, {}}}, settings);

  // The whole load in the first frame: a hard hit that the step bound must stop short.
  DynamicsSettings dynamics;
  dynamics.time_step_s = 0.01;
  dynamics.frames = 2000;
  dynamics.ramp_frames = 1;
  dynamics.until_converged = true;
  dynamics.convergence_tolerance = 1e-7;
  dynamics.density_kg_m3 = 1100.0;
  dynamics.mass_damping_per_s = 10.0;
  dynamics.linear_solver = LinearSolverKind::direct;
  ImplicitEuler solver(body, conditions, dynamics);
  solver.set_extra_potential(&contact);
  Eigen::VectorXd x = body.rest_positions();
  double lowest = INFINITY;
  const DynamicResult result =
      solver.run(x, [&](const FrameReport&, const Eigen::VectorXd& state, const Eigen::VectorXd&) {
        for (Eigen::Index n = 0; n < state.size() / 3; ++n)
          lowest = std::min(lowest, state(3 * n + 2));
      });
  ASSERT_TRUE(result.completed) << result.failure;
  EXPECT_GT(result.frames, 3); // the first frame stops at 80 % of the gap, then it settles
  EXPECT_GT(lowest, 0.0);
  const ContactMeasures measures = contact.measure(x, 1.0);
  EXPECT_NEAR(measures.force_n[0].z(), total_n, 1e-5 * total_n);
}

namespace {

/// A 20 x 2 x 0.5 mm band on top of a capped cylinder of radius 3 mm (axis y), one end fixed,
/// the other end carried a quarter turn around the cylinder and pulled 2 mm on.
struct BandOverCylinder {
  ligsim::TetMesh mesh = [] {
    ligsim::TetMesh m = structured_box_mesh({40, 4, 1}, {20.0, 2.0, 0.5});
    m.V.col(0).array() -= 10.0;
    m.V.col(1).array() -= 1.0;
    m.V.col(2).array() += 3.1;
    return m;
  }();
  MaterialParameters material = ground_substance();
  HyperelasticBody body{mesh, material, no_fibers()};
  BoundaryConditions conditions = [this] {
    BoundaryConditions c;
    ConstraintSet fixed;
    fixed.name = "fixed";
    fixed.nodes = nodes_on_plane(mesh.V, 0, -10.0, 1e-9);
    ConstraintSet pulled;
    pulled.name = "pulled";
    pulled.nodes = nodes_on_plane(mesh.V, 0, 10.0, 1e-9);
    RigidMotion wrap;
    wrap.axis = Eigen::Vector3d::UnitY();
    wrap.angle_rad = M_PI / 2.0;
    wrap.translation_mm = Eigen::Vector3d(0.0, 0.0, -2.0);
    pulled.rigid = wrap;
    c.constraints = {fixed, pulled};
    return c;
  }();
  static constexpr double radius = 3.0;
  BoneLevelSet cylinder{test::cylinder_surface(radius, 5.0, 256), {0.1, 0.6}};
  ContactSettings settings = [] {
    ContactSettings c;
    c.d_hat_mm = 0.3;
    return c;
  }();
  ContactPotential contact =
      boundary_contact(mesh, conditions, {{"cylinder", &cylinder, std::nullopt, {}}}, settings);
};

/// An extra potential that hands the solver only its projected Hessian.
class ProjectedOnly final : public ExtraPotential {
public:
  explicit ProjectedOnly(const ExtraPotential& inner)
      : m_inner(inner)
  {
  }
  double energy(const Eigen::VectorXd& x, double t, Eigen::VectorXd* gradient) const override
  {
    return m_inner.energy(x, t, gradient);
  }
  void hessian_blocks(const Eigen::VectorXd& x, double t, bool,
                      std::vector<NodeBlock>& blocks) const override
  {
    m_inner.hessian_blocks(x, t, true, blocks);
  }
  double max_step(const Eigen::VectorXd& x, const Eigen::VectorXd& dx, double t) const override
  {
    return m_inner.max_step(x, dx, t);
  }
  int make_admissible(Eigen::VectorXd& x, double t) const override
  {
    return m_inner.make_admissible(x, t);
  }

private:
  const ExtraPotential& m_inner;
};

} // namespace

TEST(ContactSolvers, BandPulledOverACylinderBalancesItsEndTensions)
{
  BandOverCylinder band;
  const ContactPotential& contact = band.contact;
  const BoundaryConditions& conditions = band.conditions;
  const double radius = BandOverCylinder::radius;
  const ContactSettings& settings = band.settings;
  const ligsim::TetMesh& mesh = band.mesh;

  NewtonSettings newton;
  newton.load_steps = 10;
  newton.residual_tolerance = 1e-10;
  StaticSolver solver(band.body, conditions, newton);
  solver.set_extra_potential(&contact);
  Eigen::VectorXd x = band.body.rest_positions();
  Eigen::VectorXd residual;
  const StaticResult result = solver.solve(x, [&](const StepReport&, const Eigen::VectorXd&,
                                                  const Eigen::VectorXd& r) { residual = r; });
  ASSERT_TRUE(result.converged) << result.failure;

  const std::vector<Eigen::Vector3d> ends = reaction_forces(conditions, residual);
  const Eigen::Vector3d tensions = ends[0] + ends[1];
  const ContactMeasures measures = contact.measure(x, 1.0);
  const Eigen::Vector3d& force = measures.force_n[0];
  EXPECT_GT(tensions.norm(), 1.0); // N: the band is pulled hard
  EXPECT_LT((force + tensions).norm(), 0.01 * tensions.norm());
  // The ends pull along -x and -z: the cylinder pushes the band out along the bisector.
  EXPECT_GT(force.normalized().dot(Eigen::Vector3d(1, 0, 1).normalized()), std::cos(0.2));
  double deepest = 0.0;
  for (Eigen::Index n = 0; n < mesh.V.rows(); ++n) {
    const Eigen::Vector3d p = x.segment<3>(3 * n);
    deepest = std::min(deepest, std::hypot(p.x(), p.z()) - radius);
  }
  EXPECT_GT(deepest, -0.01 * settings.d_hat_mm);
  EXPECT_GT(measures.active_nodes[0], 20);
}

TEST(ContactSolvers, NewtonConvergesQuadraticallyOnNodesSlidingOverACurvedObstacle)
{
  // The barrier's projected Hessian drops the cylinder's curvature (b' R H R^T, negative along
  // the surface) and Newton converges only linearly on the band's sliding nodes; the exact one,
  // where the matrix stays definite with it, gives Newton's quadratic rate: far fewer iterations
  // to the same state.
  BandOverCylinder band;
  NewtonSettings newton;
  newton.load_steps = 10;
  newton.residual_tolerance = 1e-10;
  const ProjectedOnly projected(band.contact);
  Eigen::VectorXd x_exact = band.body.rest_positions();
  Eigen::VectorXd x_projected = x_exact;
  StaticSolver exact_solver(band.body, band.conditions, newton);
  exact_solver.set_extra_potential(&band.contact);
  const StaticResult exact = exact_solver.solve(x_exact);
  StaticSolver projected_solver(band.body, band.conditions, newton);
  projected_solver.set_extra_potential(&projected);
  const StaticResult linear = projected_solver.solve(x_projected);
  ASSERT_TRUE(exact.converged) << exact.failure;
  ASSERT_TRUE(linear.converged) << linear.failure;
  EXPECT_LT((x_exact - x_projected).lpNorm<Eigen::Infinity>(), 1e-6); // mm
  EXPECT_LT(2 * exact.newton_iterations, linear.newton_iterations)
      << exact.newton_iterations << " Newton iterations with the exact Hessian, "
      << linear.newton_iterations << " with the projected one";
}

TEST(ContactSolvers, ImplicitEulerFramesOfASoftBandFollowTheQuasiStaticWrap)
{
  // The band of Gardiner & Weiss' human MCL ground substance (mu 2.88 MPa, K 793.65 MPa, ln J),
  // wrapped in 100 frames of 0.01 s: slow enough that inertia is negligible, so each frame should
  // be the quasi-static state of its pose. One linearised solve per frame leaves each frame's
  // error in the state, and it builds up; Newton iterations on the frame's equation remove it.
  BandOverCylinder band;
  band.material.mu_mpa = 2.88;
  band.material.bulk_modulus_mpa = 793.65;
  band.material.volumetric = VolumetricLaw::lnj;
  const HyperelasticBody body(band.mesh, band.material, no_fibers());
  NewtonSettings newton;
  newton.load_steps = 10;
  StaticSolver quasi_static(body, band.conditions, newton);
  quasi_static.set_extra_potential(&band.contact);
  Eigen::VectorXd x_static = body.rest_positions();
  Eigen::VectorXd residual;
  ASSERT_TRUE(quasi_static
                  .solve(x_static, [&](const StepReport&, const Eigen::VectorXd&,
                                       const Eigen::VectorXd& r) { residual = r; })
                  .converged);
  const double reaction = reaction_forces(band.conditions, residual)[1].norm();
  const auto frames = [&](int max_iterations) {
    DynamicsSettings dynamics;
    dynamics.time_step_s = 0.01;
    dynamics.frames = 100;
    dynamics.ramp_frames = 100;
    dynamics.density_kg_m3 = 1100.0;
    dynamics.mass_damping_per_s = 10.0;
    dynamics.linear_solver = LinearSolverKind::direct;
    dynamics.max_iterations = max_iterations;
    ImplicitEuler solver(body, band.conditions, dynamics);
    solver.set_extra_potential(&band.contact);
    Eigen::VectorXd x = body.rest_positions();
    double largest = 0.0, last = 0.0;
    const DynamicResult result =
        solver.run(x, [&](const FrameReport&, const Eigen::VectorXd&, const Eigen::VectorXd& r) {
          last = reaction_forces(band.conditions, r)[1].norm();
          largest = std::max(largest, last);
        });
    EXPECT_TRUE(result.completed) << result.failure;
    return std::make_tuple((x - x_static).lpNorm<Eigen::Infinity>(), last, largest);
  };
  const auto [one_error, one_last, one_largest] = frames(1);
  const auto [newton_error, newton_last, newton_largest] = frames(4);
  EXPECT_LT(newton_error, 0.05); // mm
  EXPECT_NEAR(newton_last, reaction, 0.02 * reaction);
  EXPECT_LT(newton_largest, 1.02 * reaction);
  // One solve per frame ends 1.1 mm off, pulling 4 times as hard (11 against 2.5 N).
  EXPECT_GT(one_error, 10 * newton_error);
  EXPECT_GT(one_last, 2 * reaction);
}
