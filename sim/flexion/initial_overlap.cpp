#include "sim/flexion/initial_overlap.hpp"

#include "common/error.hpp"
#include "sim/solver/static_solver.hpp"

#include <algorithm>

namespace ligsim::sim {

namespace {

/// The same node sets, each held where it is.
BoundaryConditions held_in_place(const BoundaryConditions& conditions)
{
  BoundaryConditions held = conditions;
  for (ConstraintSet& set : held.constraints) {
    set.rigid.reset();
    set.components = {true, true, true};
    set.displacement_mm.setZero();
  }
  held.loads.clear();
  return held;
}

} // namespace

OverlapReport resolve_initial_overlap(const HyperelasticBody& body,
                                      const BoundaryConditions& conditions,
                                      const KneeContact& contact, const NewtonSettings& newton,
                                      Eigen::VectorXd& x)
{
  OverlapReport report;
  report.before = contact.gaps(x, 0.0);
  const double d_hat = contact.potential().settings().d_hat_mm;
  bool any_inside = false;
  for (const KneeContact::Gaps& g : report.before) {
    any_inside = any_inside || g.inside > 0;
    report.start_offsets_mm.push_back(g.inside > 0 ? -g.min_gap_mm + 0.5 * d_hat : 0.0);
  }
  if (!any_inside)
    return report;

  // The nodes that start inside, to say how far they moved.
  std::vector<int> inside;
  for (const KneeContact::Gaps& g : report.before)
    inside.insert(inside.end(), g.inside_nodes.begin(), g.inside_nodes.end());

  const std::unique_ptr<ContactPotential> growing =
      contact.resting_bones_shrunk_by(report.start_offsets_mm);
  NewtonSettings settings = newton;
  settings.load_factors = {0.25, 0.5, 0.75, 1.0};
  StaticSolver solver(body, held_in_place(conditions), settings);
  solver.set_extra_potential(growing.get());
  const Eigen::VectorXd start = x;
  const StaticResult result = solver.solve(x);
  if (!result.converged)
    fail<SolverError>(
        "pushing the ligament's nodes out of the bones they overlap as segmented "
        "(up to {:.3g} mm deep): {}",
        *std::max_element(report.start_offsets_mm.begin(), report.start_offsets_mm.end()) -
            0.5 * d_hat,
        result.failure);
  report.pushed = true;
  report.newton_iterations = result.newton_iterations;
  report.after = contact.gaps(x, 0.0);
  for (Eigen::Index n = 0; n < x.size() / 3; ++n)
    report.max_node_move_mm =
        std::max(report.max_node_move_mm, (x.segment<3>(3 * n) - start.segment<3>(3 * n)).norm());
  for (int n : inside)
    report.mean_surface_move_mm += (x.segment<3>(3 * n) - start.segment<3>(3 * n)).norm();
  report.mean_surface_move_mm /= static_cast<double>(inside.size());
  return report;
}

OverlapReport reshape_initial_overlap(const HyperelasticBody& body,
                                      const MaterialParameters& material,
                                      const BoundaryConditions& conditions,
                                      const KneeContact& contact, const NewtonSettings& newton,
                                      Eigen::VectorXd& x)
{
  OverlapReport report =
      resolve_initial_overlap(with_unit_fibers(body, material), conditions, contact, newton, x);
  report.reshaped = report.pushed;
  return report;
}

KneeModel with_overlap_reshaped(const KneeModel& model, const FlexionSettings& settings,
                                const BoundaryConditions& conditions, const KneeContact& contact,
                                OverlapReport* report)
{
  // The push leaves the in-situ strain out, so the model's unit fibers serve.
  const HyperelasticBody body = ligament_body(model, settings.material, 0.0);
  Eigen::VectorXd x = body.rest_positions();
  const OverlapReport pushed =
      reshape_initial_overlap(body, settings.material, conditions, contact, settings.newton, x);
  if (report)
    *report = pushed;
  KneeModel reshaped = model;
  if (pushed.pushed)
    for (Eigen::Index n = 0; n < reshaped.mesh.V.rows(); ++n)
      reshaped.mesh.V.row(n) = x.segment<3>(3 * n).transpose();
  return reshaped;
}

HyperelasticBody with_unit_fibers(const HyperelasticBody& body, const MaterialParameters& material)
{
  FiberField unit(body.element_count(), 3);
  for (Eigen::Index e = 0; e < body.element_count(); ++e)
    unit.row(e) = body.fiber(e).stableNormalized().transpose(); // zero without fibers
  return body.with(body.mesh().V, std::move(unit), material);
}

HyperelasticBody with_rest_shape(const HyperelasticBody& body, const MaterialParameters& material,
                                 const Eigen::VectorXd& x)
{
  Points rest(body.node_count(), 3);
  for (Eigen::Index n = 0; n < rest.rows(); ++n)
    rest.row(n) = x.segment<3>(3 * n).transpose();
  FiberField fibers(body.element_count(), 3);
  for (Eigen::Index e = 0; e < body.element_count(); ++e)
    fibers.row(e) = body.fiber(e).transpose();
  return body.with(rest, std::move(fibers), material);
}

} // namespace ligsim::sim
