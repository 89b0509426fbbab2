#include "sim/verify/contact_stability.hpp"

#include "common/error.hpp"
#include "common/resources.hpp"
#include "sim/contact/bone_level_set.hpp"
#include "sim/contact/contact_potential.hpp"
#include "sim/contact/contact_surface.hpp"
#include "sim/mesh/node_selection.hpp"
#include "sim/mesh/sphere_surface.hpp"
#include "sim/mesh/structured_mesh.hpp"
#include "sim/solver/static_solver.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>

namespace ligsim::sim {

namespace {

constexpr double sphere_radius_mm = 3.0;

struct ContactCase {
  StabilityCase info;
  double d_hat_mm = 0.1;
  double start_gap_mm = 0.1; ///< band bottom above the sphere's top; negative: inside
  double lift_mm = 2.0;      ///< the sphere's move into the band, in one load step
};

std::vector<ContactCase> contact_cases()
{
  std::vector<ContactCase> list;
  for (double d_hat : {0.01, 0.1, 1.0})
    list.push_back({{fmt::format("contact_push_2mm_d_hat_{:g}", d_hat),
                     fmt::format("8 x 2 x 1 mm band held at both ends, a rigid sphere (r 3 mm) "
                                 "0.1 mm below moved 2 mm into it in one load step, d_hat {:g} mm",
                                 d_hat)},
                    d_hat,
                    0.1,
                    2.0});
  list.push_back({{"contact_node_inside_bone",
                   "the band's bottom nodes start 0.2 mm inside the sphere (within the grid's "
                   "band): pushed out, then equilibrium"},
                  0.1,
                  -0.2,
                  0.0});
  list.push_back({{"contact_node_deep_inside_bone",
                   "the band's bottom nodes start 1.5 mm inside the sphere, beyond the grid's "
                   "band: no way out is known"},
                  0.1,
                  -1.5,
                  0.0});
  return list;
}

StabilityResult run_case(const ContactCase& c)
{
  StabilityResult result;
  result.name = c.info.name;
  result.description = c.info.description;
  const auto start = std::chrono::steady_clock::now();
  try {
    const TetMesh mesh = structured_box_mesh({16, 4, 2}, {8.0, 2.0, 1.0});
    FiberField along_band(1, 3);
    along_band << 1.0, 0.0, 0.0;
    const HyperelasticBody body(mesh, mcl_material(), along_band);
    BoundaryConditions conditions;
    ConstraintSet left, right;
    left.name = "left";
    left.nodes = nodes_on_plane(mesh.V, 0, 0.0, 1e-9);
    right.name = "right";
    right.nodes = nodes_on_plane(mesh.V, 0, 8.0, 1e-9);
    conditions.constraints = {left, right};

    const Eigen::Vector3d centre(4.0, 1.0, -sphere_radius_mm - c.start_gap_mm);
    const BoneLevelSet sphere(sphere_surface(centre, sphere_radius_mm, 5),
                              {0.1, std::max(0.5, c.d_hat_mm + 0.2)});
    RigidMotion lift;
    lift.translation_mm = Eigen::Vector3d(0.0, 0.0, c.lift_mm);
    ContactSettings settings;
    settings.d_hat_mm = c.d_hat_mm;
    const ContactPotential contact(body.node_count(), free_boundary_surface(mesh, conditions),
                                   {{"sphere", &sphere, lift, {}}}, settings);

    NewtonSettings newton;
    newton.load_steps = 1;
    newton.max_cutbacks = 12;
    StaticSolver solver(body, conditions, newton);
    solver.set_extra_potential(&contact);
    Eigen::VectorXd x = body.rest_positions();
    Eigen::VectorXd residual;
    const StaticResult run = solver.solve(x, [&](const StepReport&, const Eigen::VectorXd&,
                                                 const Eigen::VectorXd& r) { residual = r; });
    result.converged = run.converged;
    result.diagnostic = run.failure;
    result.iterations = run.newton_iterations;
    result.min_j = body.min_j(x).first;
    const Eigen::VectorXd rest = body.rest_positions();
    double deepest = 0.0; // into the exact sphere, mm
    const Eigen::Vector3d moved_centre = centre + lift.translation_mm;
    for (int node = 0; node < body.node_count(); ++node) {
      result.max_displacement_mm = std::max(
          result.max_displacement_mm, (x.segment<3>(3 * node) - rest.segment<3>(3 * node)).norm());
      deepest =
          std::max(deepest, sphere_radius_mm - (x.segment<3>(3 * node) - moved_centre).norm());
    }
    if (result.converged && residual.size() == x.size()) {
      const Eigen::Vector3d force = contact.measure(x, 1.0).force_n[0];
      const std::vector<Eigen::Vector3d> ends = reaction_forces(conditions, residual);
      result.balance_error = (ends[0] + ends[1] + force).norm() / std::max(force.norm(), 1e-300);
      result.description +=
          fmt::format(" (contact force {:.3g} N, deepest node {:.2g} mm inside the exact sphere, "
                      "{} cut-backs)",
                      force.norm(), deepest, run.cutbacks);
    }
    result.outcome = static_outcome(result, x, deepest < 0.05);
  } catch (const Error& e) {
    result.diagnostic = e.what();
    result.outcome = Outcome::diagnostic;
  }
  result.wall_s = seconds_since(start);
  return result;
}

} // namespace

std::vector<StabilityCase> contact_stability_cases()
{
  std::vector<StabilityCase> cases;
  for (const ContactCase& c : contact_cases())
    cases.push_back(c.info);
  return cases;
}

std::optional<StabilityResult> run_contact_stability_case(const std::string& name)
{
  for (const ContactCase& c : contact_cases())
    if (c.info.name == name)
      return run_case(c);
  return std::nullopt;
}

} // namespace ligsim::sim
