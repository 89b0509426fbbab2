#include "sim/solver/static_solver.hpp"

#include "common/error.hpp"
#include "common/progress.hpp"
#include "common/resources.hpp"
#include "sim/solver/substep_controller.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace ligsim::sim {

namespace {

constexpr int max_line_search_steps = 30;
constexpr double armijo = 1e-4;
/// Relative size of an energy change that round-off can produce in the element sum.
constexpr double energy_round_off = 1e-12;
/// Trials of a saddle step's residual line search (steps 1, 1/2, 1/4) before falling back to
/// the projected step: far from a saddle equilibrium the unprojected step only crawls.
constexpr int max_residual_search_steps = 3;

} // namespace

PsdProjection parse_psd_projection(const std::string& text, const std::string& where)
{
  if (text == "auto")
    return PsdProjection::automatic;
  if (text == "always")
    return PsdProjection::always;
  if (text == "never")
    return PsdProjection::never;
  fail("{}: psd_projection must be \"auto\", \"always\" or \"never\", got \"{}\"", where, text);
}

std::string to_string(PsdProjection projection)
{
  switch (projection) {
  case PsdProjection::automatic:
    return "auto";
  case PsdProjection::always:
    return "always";
  case PsdProjection::never:
    return "never";
  }
  return "auto";
}

StaticSolver::StaticSolver(const HyperelasticBody& body, const BoundaryConditions& conditions,
                           const NewtonSettings& settings)
    : m_body(body)
    , m_conditions(conditions)
    , m_settings(settings)
    , m_dofs(body.node_count(), conditions, body.unreferenced_nodes())
    , m_rest(body.rest_positions())
    , m_external(m_dofs.external_forces(conditions))
    , m_linear(body, m_dofs, settings.linear_solver, settings.pcg)
    , m_tangent(body, m_dofs, m_linear.direct())
    , m_convergence(
          settings.residual_tolerance, settings.energy_tolerance,
          (body.mesh().V.colwise().maxCoeff() - body.mesh().V.colwise().minCoeff()).norm())
{
  if (settings.load_steps < 1)
    fail("solver: load_steps must be at least 1, got {}", settings.load_steps);
  for (std::size_t i = 0; i < settings.load_factors.size(); ++i) {
    const double t = settings.load_factors[i];
    const double previous = i == 0 ? 0.0 : settings.load_factors[i - 1];
    if (!(t >= previous && t <= 1.0) || (i > 0 && t == previous))
      fail("solver: load factors must increase within [0, 1]; factor {} is {}", i + 1, t);
  }
  if (settings.max_iterations < 1)
    fail("solver: max_iterations must be at least 1, got {}", settings.max_iterations);
  if (settings.max_substeps < 1)
    fail("solver: max_substeps must be at least 1, got {}", settings.max_substeps);
  if (!(settings.residual_tolerance > 0.0))
    fail("solver: residual_tolerance must be positive, got {}", settings.residual_tolerance);
  if (m_dofs.free_count() == 0)
    fail("every degree of freedom is prescribed: nothing to solve");
  const Tetrahedra& T = body.mesh().T;
  for (Eigen::Index e = 0; e < T.rows(); ++e)
    for (int i = 0; i < 4; ++i)
      if (!m_dofs.is_free(3 * T(e, i)) || !m_dofs.is_free(3 * T(e, i) + 1) ||
          !m_dofs.is_free(3 * T(e, i) + 2)) {
        m_boundary_elements.push_back(static_cast<int>(e));
        break;
      }
  const Points& V = body.mesh().V;
  const double size = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  m_force_floor = 1e-12 * body.material().parameters().mu_mpa * size * size;
  m_energy_unit = body.material().parameters().mu_mpa * body.rest_volume();

  Eigen::VectorXd lumped = Eigen::VectorXd::Zero(body.dof_count());
  double mean_size_squared = 0.0;
  for (Eigen::Index e = 0; e < T.rows(); ++e) {
    const double volume = body.shape(static_cast<int>(e)).V0;
    mean_size_squared += std::pow(volume, 2.0 / 3.0) / static_cast<double>(T.rows());
    for (int i = 0; i < 4; ++i)
      lumped.segment<3>(3 * T(e, i)).array() += volume / 4.0;
  }
  m_shift_unit = m_dofs.gather(lumped) * (body.material().parameters().mu_mpa / mean_size_squared);
}

std::vector<double> StaticSolver::step_targets() const
{
  if (!m_settings.load_factors.empty())
    return m_settings.load_factors;
  std::vector<double> targets;
  for (int step = 1; step <= m_settings.load_steps; ++step)
    targets.push_back(static_cast<double>(step) / m_settings.load_steps);
  return targets;
}

void StaticSolver::evaluate(const Eigen::VectorXd& x, double t, Evaluation& out) const
{
  out.body = m_body.energy_gradient(x, out.gradient);
  out.gradient -= t * m_external;
  out.total_energy = out.body.energy - t * m_external.dot(x - m_rest);
  if (m_extra && std::isfinite(out.body.energy)) {
    const double extra = m_extra->energy(x, t, &out.gradient);
    out.extra_inadmissible = !std::isfinite(extra);
    out.total_energy += extra;
  }
}

double StaticSolver::relative_residual(const Eigen::VectorXd& gradient, double t1) const
{
  double free2 = 0.0;
  double reaction2 = 0.0;
  for (int dof = 0; dof < m_dofs.dof_count(); ++dof)
    (m_dofs.is_free(dof) ? free2 : reaction2) += gradient(dof) * gradient(dof);
  return std::sqrt(free2) /
         std::max({(t1 * m_external).norm(), std::sqrt(reaction2), m_force_floor});
}

std::string StaticSolver::describe_inversion(const BodyEnergy& energy) const
{
  if (energy.first_inverted < 0)
    return "a node would cross a contact surface";
  return fmt::format("element {} inverts (J = {:.3g})", energy.first_inverted, energy.inverted_j);
}

bool StaticSolver::newton_direction(const Eigen::VectorXd& x, double t, const Eigen::VectorXd& rhs,
                                    Eigen::VectorXd& direction, StepReport& report,
                                    bool allow_saddle, bool& saddle)
{
  saddle = false;
  if (m_shifted)
    return shifted_direction(x, t, rhs, direction, report);
  bool project = m_settings.projection == PsdProjection::always;
  // The extra potential's exact Hessian first: a contact barrier's projected Hessian drops the
  // obstacle's curvature, and Newton converges only linearly on nodes that slide over it.
  bool exact_extra = m_extra && !project;
  std::vector<NodeBlock> blocks;
  if (m_extra)
    m_extra->hessian_blocks(x, t, !exact_extra, blocks);
  for (;;) {
    report.projected_elements += m_linear.prepare(x, project, 1.0, Eigen::VectorXd(), blocks);
    direction = Eigen::VectorXd::Zero(rhs.size());
    const LinearSolveReport solve = m_linear.solve(rhs, direction);
    report.linear_iterations += solve.iterations;
    report.factorizations += solve.factorizations;
    // A Newton step must go downhill in energy: rhs is minus the gradient.
    const bool downhill = solve.ok && direction.allFinite() && direction.dot(rhs) > 0.0;
    if (downhill)
      return true;
    if (exact_extra && (solve.indefinite || solve.ok)) {
      // Indefinite with the exact extra Hessian: its projection next, then the elements'.
      exact_extra = false;
      blocks.clear();
      m_extra->hessian_blocks(x, t, true, blocks);
      continue;
    }
    if (!project && m_settings.projection == PsdProjection::automatic &&
        (solve.indefinite || solve.ok)) {
      ++report.indefinite_iterations;
      // The unprojected Newton step converges quadratically to a saddle equilibrium (a state
      // past a bifurcation), where the projected one crawls or walks away from it.
      // The factorised tangent is the body's alone: no saddle step with an extra potential.
      const int factorizations_before = m_tangent.factorizations();
      const bool factorized = allow_saddle && !m_extra && m_tangent.factorize(x);
      report.factorizations += m_tangent.factorizations() - factorizations_before;
      if (factorized) {
        direction = m_tangent.solve(rhs);
        if (direction.allFinite()) {
          saddle = true;
          return true;
        }
      }
      project = true;
      continue;
    }
    if (solve.indefinite)
      m_failure = project ? "the projected stiffness matrix is singular (are rigid motions "
                            "constrained?)"
                          : "the stiffness matrix is indefinite (psd_projection = never)";
    else if (!solve.ok)
      m_failure = fmt::format("the linear solver did not converge (relative residual {:.3g} "
                              "after {} CG iterations)",
                              solve.relative_residual, solve.iterations);
    else
      m_failure = "the Newton direction does not decrease the energy";
    return false;
  }
}

bool StaticSolver::shifted_direction(const Eigen::VectorXd& x, double t, const Eigen::VectorXd& rhs,
                                     Eigen::VectorXd& direction, StepReport& report)
{
  constexpr double first_shift = 1e-2, largest_shift = 1e6;
  std::vector<NodeBlock> blocks;
  if (m_extra)
    m_extra->hessian_blocks(x, t, false, blocks);
  // D: the body's stiffness scale plus the size of the extra potential's diagonal, per DOF.
  Eigen::VectorXd unit = m_shift_unit;
  for (const NodeBlock& block : blocks)
    for (int k = 0; k < 3; ++k)
      if (const int f = m_dofs.free_index(3 * block.node + k); f >= 0)
        unit(f) += std::abs(block.block(k, k));
  // Unshifted first: near a stable equilibrium this is Newton's own step, converging
  // quadratically; then from a third of the shift that last worked.
  double shift = 0.0;
  for (;;) {
    const Eigen::VectorXd diagonal =
        shift > 0.0 ? Eigen::VectorXd(shift * unit) : Eigen::VectorXd();
    m_linear.prepare(x, false, 1.0, diagonal, blocks);
    direction = Eigen::VectorXd::Zero(rhs.size());
    const LinearSolveReport solve = m_linear.solve(rhs, direction);
    report.linear_iterations += solve.iterations;
    report.factorizations += solve.factorizations;
    if (solve.ok && direction.allFinite() && direction.dot(rhs) > 0.0) {
      if (shift > 0.0) {
        ++report.shifted_iterations;
        m_shift = shift;
      }
      if (m_settings.verbose && shift > 0.0)
        log_info(fmt::format("load {:.4g}: Newton step shifted by {:.3g} D", t, shift));
      return true;
    }
    if (shift == 0.0)
      ++report.indefinite_iterations;
    shift = shift == 0.0 ? std::max(first_shift, m_shift / 3.0) : 10.0 * shift;
    if (shift > largest_shift) {
      m_failure = fmt::format("no shifted Newton step up to {:.0e} D goes downhill", largest_shift);
      return false;
    }
  }
}

std::optional<StabilityMode> StaticSolver::stability_mode(const Eigen::VectorXd& x)
{
  if (!m_tangent.factorize(x))
    return std::nullopt;
  return m_tangent.lowest_mode(m_dofs.gather(m_external));
}

bool StaticSolver::move_prescribed(Eigen::VectorXd& x, double t1, StepReport& report)
{
  Eigen::VectorXd target = x;
  m_dofs.apply_targets(m_conditions, m_body.mesh().V, t1, target);
  const Eigen::VectorXd shift = target - x;
  if (shift.lpNorm<Eigen::Infinity>() == 0.0)
    return true;

  // Linear predictor: K_ff d = -(r_f + K_fc shift), with K at the converged state x (the extra
  // potential's obstacles where they were there).
  Evaluation at;
  evaluate(x, m_extra ? m_converged_t : t1, at);
  if (m_extra)
    at.gradient -= (t1 - m_converged_t) * m_external;
  Eigen::VectorXd coupling = Eigen::VectorXd::Zero(m_dofs.dof_count());
  const Tetrahedra& T = m_body.mesh().T;
  ElementEvaluation element;
  for (int e : m_boundary_elements) {
    Vector12d local_shift;
    for (int i = 0; i < 4; ++i)
      local_shift.segment<3>(3 * i) = shift.segment<3>(3 * T(e, i));
    if (local_shift.lpNorm<Eigen::Infinity>() == 0.0)
      continue;
    m_body.material().evaluate(tet_corners(T, e, x), m_body.shape(e), m_body.fiber(e),
                               ElementNeeds::hessian, element);
    const Vector12d force = element.hessian * local_shift;
    for (int i = 0; i < 4; ++i)
      coupling.segment<3>(3 * T(e, i)) += force.segment<3>(3 * i);
  }
  const Eigen::VectorXd rhs = -m_dofs.gather(at.gradient + coupling);
  Eigen::VectorXd predictor;
  bool saddle = false;
  if (!newton_direction(x, m_converged_t, rhs, predictor, report, true, saddle))
    predictor = Eigen::VectorXd::Zero(rhs.size()); // the prescribed move alone, checked below

  BodyEnergy energy;
  for (double alpha = 1.0; alpha > 1e-3; alpha *= 0.5) {
    Eigen::VectorXd trial = target;
    m_dofs.scatter_add(predictor, alpha, trial);
    if (m_extra)
      m_extra->make_admissible(trial, t1);
    energy = m_body.energy(trial);
    if (m_extra && std::isfinite(energy.energy) &&
        !std::isfinite(m_extra->energy(trial, t1, nullptr)))
      energy = BodyEnergy{INFINITY, -1, 1.0};
    if (std::isfinite(energy.energy)) {
      x = trial;
      return true;
    }
  }
  m_failure = fmt::format("moving the prescribed nodes to load factor {:.4g}: {}", t1,
                          describe_inversion(energy));
  return false;
}

bool StaticSolver::line_search(const Eigen::VectorXd& x, const Evaluation& current,
                               const Eigen::VectorXd& direction, bool saddle, double t1,
                               StepReport& report, Eigen::VectorXd& x_trial, Evaluation& trial,
                               double& alpha)
{
  const Eigen::VectorXd residual = m_dofs.gather(current.gradient);
  const double slope = residual.dot(direction); // < 0 for an energy step
  auto step_to = [&](double a) {
    x_trial = x;
    m_dofs.scatter_add(direction, a, x_trial);
    evaluate(x_trial, t1, trial);
  };
  // An extra potential bounds the step: no node crosses a contact surface on the way.
  alpha = m_extra ? std::min(1.0, m_extra->max_step(x, m_dofs.expand(direction), t1)) : 1.0;
  if (saddle) {
    // The Newton step decreases |r|^2 at the rate 2 |r|^2 whatever the inertia of K.
    const double norm = residual.norm();
    for (int k = 0; k < max_residual_search_steps; ++k, alpha *= 0.5) {
      step_to(alpha);
      if (std::isfinite(trial.total_energy) &&
          m_dofs.gather(trial.gradient).norm() <= (1.0 - armijo * alpha) * norm)
        return true;
      ++report.line_search_backtracks;
    }
    return false;
  }

  // Backtracking line search on the total energy.
  // Round-off in the element sum scales with the material's energy per volume, even where
  // the strain energy itself is near zero (rigid motions).
  const double energy_scale =
      std::abs(current.body.energy) + std::abs(t1 * m_external.dot(x - m_rest)) + m_energy_unit;
  BodyEnergy last_inversion;
  for (int k = 0; k < max_line_search_steps; ++k) {
    step_to(alpha);
    if (std::isfinite(trial.total_energy) && alpha > 0.0) {
      const double change = trial.total_energy - current.total_energy;
      if (change <= armijo * alpha * slope)
        return true;
      if (std::abs(change) <= energy_round_off * energy_scale &&
          m_dofs.gather(trial.gradient).norm() < residual.norm())
        return true; // the energy is flat to round-off: accept a smaller residual
      // Minimiser of the quadratic through E(0), E'(0) and E(alpha), kept in [0.1, 0.5] alpha.
      const double curvature = change - alpha * slope;
      const double next = curvature > 0.0 ? -slope * alpha * alpha / (2.0 * curvature) : 0.5;
      alpha = std::clamp(next, 0.1 * alpha, 0.5 * alpha);
    } else {
      last_inversion = trial.body;
      alpha *= 0.5;
    }
    ++report.line_search_backtracks;
  }
  m_failure = last_inversion.first_inverted >= 0
                  ? fmt::format("the line search found no admissible step: {}",
                                describe_inversion(last_inversion))
                  : "the line search found no energy decrease";
  return false;
}

bool StaticSolver::advance(Eigen::VectorXd& x, double t1, StepReport& report)
{
  constexpr int shifted_iteration_factor = 10;
  if (m_dofs.has_moving_targets() && !move_prescribed(x, t1, report))
    return false;
  const int pushed = m_extra ? m_extra->make_admissible(x, t1) : 0;

  Evaluation current;
  evaluate(x, t1, current);
  if (!std::isfinite(current.body.energy)) {
    m_failure = describe_inversion(current.body);
    if (pushed > 0)
      m_failure = fmt::format("moving {} nodes out of a contact obstacle: {} (they started too "
                              "deep inside it)",
                              pushed, m_failure);
    return false;
  }
  if (current.extra_inadmissible) {
    m_failure = "a node lies inside a contact obstacle, too deep to be moved out (beyond the "
                "obstacle's distance band)";
    return false;
  }
  m_convergence.restart();
  int iterations = 0;
  for (;;) {
    const Eigen::VectorXd residual = m_dofs.gather(current.gradient);
    if (!residual.allFinite()) {
      m_failure = "the internal forces are not finite";
      return false;
    }
    report.relative_residual = relative_residual(current.gradient, t1);
    const ConvergenceVerdict verdict =
        m_convergence.verdict(report.relative_residual, residual.norm() <= m_force_floor);
    if (verdict == ConvergenceVerdict::converged_at_floor) {
      report.converged_at_floor = true;
      report.floor = m_convergence.floor_summary();
    }
    if (verdict != ConvergenceVerdict::iterate) {
      m_converged_t = t1;
      return true;
    }
    // A shifted sub-step descends from a saddle to the next stable state: away from the saddle
    // the residual grows while the energy falls, and the way down takes many more iterations.
    if (iterations == (m_shifted ? shifted_iteration_factor : 1) * m_settings.max_iterations) {
      m_failure = fmt::format("no convergence in {} Newton iterations (relative residual {:.3g})",
                              iterations, report.relative_residual);
      if (report.indefinite_iterations > 0)
        m_failure += fmt::format("; the stiffness matrix was indefinite in {} iterations",
                                 report.indefinite_iterations);
      return false;
    }
    ++iterations;
    ++report.iterations;

    Eigen::VectorXd direction;
    Eigen::VectorXd x_trial;
    Evaluation trial;
    double alpha = 1.0;
    bool saddle = false;
    if (!newton_direction(x, t1, -residual, direction, report, true, saddle))
      return false;
    bool moved = line_search(x, current, direction, saddle, t1, report, x_trial, trial, alpha);
    if (saddle && !moved) {
      // The unprojected step made no progress on the residual: minimise the energy instead.
      if (!newton_direction(x, t1, -residual, direction, report, false, saddle))
        return false;
      moved = line_search(x, current, direction, false, t1, report, x_trial, trial, alpha);
    }
    const double round_off =
        energy_round_off *
        (std::abs(current.body.energy) + std::abs(t1 * m_external.dot(x - m_rest)) + m_energy_unit);
    IterationFigures figures;
    figures.displacement_step_mm = direction.lpNorm<Eigen::Infinity>();
    figures.energy_round_off = round_off;
    if (!moved) {
      // At the round-off floor the energy cannot tell a better state from a worse one: when the
      // whole step would change it by less than round-off and no trial lowered the residual,
      // the iteration stagnates where it is (and the convergence test sees the floor).
      if (saddle || report.relative_residual > NewtonConvergence::max_floor ||
          std::abs(residual.dot(direction)) > round_off)
        return false;
      if (m_settings.verbose)
        log_info(fmt::format("load {:.4g} iteration {}: relative residual {:.3e}, no step "
                             "changes the energy beyond round-off (stagnating)",
                             t1, iterations, report.relative_residual));
      figures.relative_residual = report.relative_residual;
      m_convergence.record(figures);
      continue;
    }
    report.saddle_iterations += saddle ? 1 : 0;
    if (m_settings.verbose)
      log_info(fmt::format("load {:.4g} iteration {}: relative residual {:.3e}, step {:.3g}{} "
                           "({} projected elements, {} factorisations, {} CG iterations so far)",
                           t1, iterations, report.relative_residual, alpha,
                           saddle ? " (indefinite Newton)" : "", report.projected_elements,
                           report.factorizations, report.linear_iterations));
    figures.energy_change = std::abs(alpha * residual.dot(direction));
    x.swap(x_trial);
    std::swap(current, trial);
    figures.relative_residual = relative_residual(current.gradient, t1);
    m_convergence.record(figures);
  }
}

StaticResult StaticSolver::solve(Eigen::VectorXd& x, const StepCallback& on_step)
{
  const auto start = std::chrono::steady_clock::now();
  StaticResult result;
  if (x.size() != m_dofs.dof_count() || !x.allFinite()) {
    result.failure = "the initial positions are missing or not finite";
    return result;
  }
  const std::vector<double> targets = step_targets();
  const int steps = static_cast<int>(targets.size());
  m_shifted = false; // a solve that failed before may have left it on
  m_shift = 0.0;
  auto add_totals = [&](const StepReport& report) {
    result.newton_iterations += report.iterations;
    result.projected_elements += report.projected_elements;
    result.linear_iterations += report.linear_iterations;
    result.factorizations += report.factorizations;
  };
  double t = 0.0;
  SubstepController substeps; // carried from one output step to the next
  // Tenths of the load factor on stderr once a solve has run for a second (a 20,000-tet cube
  // past its bifurcation takes minutes in sub-steps of one nominal step).
  constexpr std::size_t kProgressUnits = 1000;
  Progress progress("static solve, load factor", kProgressUnits);
  std::size_t progress_done = 0;
  for (int step = 1; step <= steps; ++step) {
    const auto step_start = std::chrono::steady_clock::now();
    StepReport report;
    report.step = step;
    const double t_end = targets[static_cast<std::size_t>(step) - 1];
    const bool in_place = t_end - t <= 1e-14; // equilibrium at the current load factor
    const double t_start = t;
    int consecutive_cutbacks = 0;
    bool first = true;
    const auto k = static_cast<std::size_t>(step) - 1;
    if (!in_place && k < m_step_starts.size() && m_step_starts[k].size() == x.size()) {
      const Eigen::VectorXd saved = x;
      x = m_step_starts[k];
      ++report.substeps;
      if (advance(x, t_end, report)) {
        t = t_end;
        first = false;
      } else {
        x = saved;
      }
    }
    for (; first || t < t_end - 1e-14;) {
      first = false;
      const double t_next = in_place ? t_end : substeps.next_target(t, t_end);
      const Eigen::VectorXd saved = x;
      const int iterations_before = report.iterations;
      const int indefinite_before = report.indefinite_iterations;
      m_failure.clear();
      ++report.substeps;
      const bool floor_before = report.converged_at_floor;
      if (advance(x, t_next, report)) {
        t = t_next;
        const auto reached = static_cast<std::size_t>(t * kProgressUnits);
        if (reached > progress_done) {
          progress.advance(reached - progress_done);
          progress_done = reached;
        }
        if (!in_place)
          substeps.accepted(report.iterations - iterations_before);
        consecutive_cutbacks = 0;
        continue;
      }
      if (m_settings.verbose)
        log_info(fmt::format("load {:.4g}: sub-step from {:.4g} failed, cut back: {}", t_next, t,
                             m_failure));
      x = saved;
      report.converged_at_floor = floor_before;
      if (!m_shifted && m_extra && m_settings.projection == PsdProjection::automatic &&
          report.indefinite_iterations > indefinite_before) {
        // With an extra potential there is no saddle step, and the projected one crawls along
        // a buckling mode: the same sub-step again, with shifted Newton steps.
        m_shifted = true;
        first = true;
        continue;
      }
      ++report.cutbacks;
      ++result.cutbacks;
      ++consecutive_cutbacks;
      substeps.rejected(t_next - t);
      // Sub-steps that each succeed by a sliver between failures never exhaust the cut-backs:
      // a load step that has taken max_substeps stops too.
      const bool crawling = report.substeps >= m_settings.max_substeps;
      if (consecutive_cutbacks > m_settings.max_cutbacks || in_place || crawling) {
        // A step that met an indefinite stiffness stops at a critical point of the path when
        // the tangent at the last converged state is near singular or already indefinite.
        if (report.indefinite_iterations > 0)
          result.critical_mode = stability_mode(x);
        result.critical_load_factor = t;
        result.stop_kind = result.critical_mode ? result.critical_mode->kind() : "failed step";
        const std::string crawled =
            crawling ? fmt::format(" and {} sub-steps, the most one load step may take (its load "
                                   "factor crawled from {:.6g} to {:.6g})",
                                   report.substeps, t_start, t)
                     : "";
        result.failure = fmt::format("load step {} (load factor {:.6g}) failed after {} "
                                     "cut-backs{}: {}",
                                     step, t_next, report.cutbacks - 1, crawled, m_failure);
        if (result.critical_mode)
          result.failure +=
              fmt::format(". The path meets a {} between load factors {:.6g} "
                          "and {:.6g}: at {:.6g}, {}",
                          result.stop_kind, t, t_next, t, result.critical_mode->describe());
        report.wall_s = seconds_since(step_start);
        report.load_factor = t;
        result.steps.push_back(report);
        add_totals(report);
        result.wall_s = seconds_since(start);
        return result;
      }
    }
    report.converged = true;
    report.load_factor = t_end;
    m_shifted = false;
    m_shift = 0.0;
    if (report.indefinite_iterations > 0 && m_tangent.factorize(x)) {
      // Equilibrium reached through an indefinite stiffness: stable or not?
      report.negative_eigenvalues = m_tangent.negative_eigenvalues();
      if (report.negative_eigenvalues > 0)
        report.instability = "unstable equilibrium, past a " +
                             m_tangent.lowest_mode(m_dofs.gather(m_external)).describe();
    }
    Eigen::VectorXd gradient;
    report.strain_energy_mj = m_body.energy_gradient(x, gradient).energy;
    gradient -= t_end * m_external;
    if (m_extra)
      m_extra->energy(x, t_end, &gradient);
    std::tie(report.min_j, report.min_j_element) = m_body.min_j(x);
    report.wall_s = seconds_since(step_start);
    add_totals(report);
    result.steps.push_back(report);
    if (on_step)
      on_step(report, x, gradient);
  }
  result.converged = true;
  result.wall_s = seconds_since(start);
  return result;
}

} // namespace ligsim::sim
