#include "sim/solver/newton_engine.hpp"

#include "common/progress.hpp"

#include <fmt/format.h>

#include <algorithm>
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
/// A shifted sub-step descends from a saddle to the next stable state: away from the saddle
/// the residual grows while the energy falls, and the way down takes many more iterations.
constexpr int shifted_iteration_factor = 10;

} // namespace

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

NewtonEngine::NewtonEngine(const HyperelasticBody& body, const DofPartition& dofs,
                           const Eigen::VectorXd& external, StiffnessSolver& linear,
                           TangentInertia* tangent, PsdProjection projection)
    : m_body(body)
    , m_dofs(dofs)
    , m_external(external)
    , m_rest(body.rest_positions())
    , m_linear(linear)
    , m_tangent(tangent)
    , m_projection(projection)
{
  const Points& V = body.mesh().V;
  m_length_mm = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  const double mu = body.material().parameters().mu_mpa;
  m_force_floor = 1e-12 * mu * m_length_mm * m_length_mm;
  m_energy_unit = mu * body.rest_volume();

  // Each element's volume in equal shares to its nodes.
  const ElementNodes& T = body.elements();
  Eigen::VectorXd lumped = Eigen::VectorXd::Zero(body.dof_count());
  double mean_size_squared = 0.0;
  for (Eigen::Index e = 0; e < T.rows(); ++e) {
    const double volume = body.element_volume(e);
    mean_size_squared += std::pow(volume, 2.0 / 3.0) / static_cast<double>(T.rows());
    for (Eigen::Index i = 0; i < T.cols(); ++i)
      lumped.segment<3>(3 * T(e, i)).array() += volume / static_cast<double>(T.cols());
  }
  m_shift_unit = m_dofs.gather(lumped) * (mu / mean_size_squared);
}

void NewtonEngine::set_incremental_terms(const InertiaTerm* inertia, const DampingTerm* damping)
{
  m_inertia = inertia;
  m_damping = damping;
}

void NewtonEngine::set_shifted(bool shifted)
{
  m_shifted = shifted;
  if (!shifted)
    m_shift = 0.0;
}

void NewtonEngine::evaluate(const Eigen::VectorXd& x, double t, Evaluation& out) const
{
  out.body = m_body.energy_gradient(x, out.gradient);
  complete(x, t, out);
}

void NewtonEngine::complete(const Eigen::VectorXd& x, double t, Evaluation& out) const
{
  out.gradient -= t * m_external;
  out.total_energy = out.body.energy - t * m_external.dot(x - m_rest);
  out.extra_inadmissible = false;
  if (m_extra && std::isfinite(out.body.energy)) {
    const double extra = m_extra->energy(x, t, &out.gradient);
    out.extra_inadmissible = !std::isfinite(extra);
    out.total_energy += extra;
  }
  out.free_gradient = m_dofs.gather(out.gradient);
  if (m_inertia) {
    const Eigen::VectorXd offset = m_dofs.gather(x) - m_inertia->target;
    out.total_energy += 0.5 * offset.dot(m_inertia->weight.cwiseProduct(offset));
    out.free_gradient += m_inertia->weight.cwiseProduct(offset);
  }
  if (m_damping && m_damping->factor > 0.0) {
    const Eigen::VectorXd offset = m_dofs.gather(x) - m_damping->start;
    Eigen::VectorXd force = m_damping->K_s->selfadjointView<Eigen::Lower>() * offset;
    force *= m_damping->factor;
    out.total_energy += 0.5 * offset.dot(force);
    out.free_gradient += force;
  }
}

double NewtonEngine::reaction_norm(const Eigen::VectorXd& gradient) const
{
  double reaction2 = 0.0;
  for (int dof = 0; dof < m_dofs.dof_count(); ++dof)
    if (!m_dofs.is_free(dof))
      reaction2 += gradient(dof) * gradient(dof);
  return std::sqrt(reaction2);
}

double NewtonEngine::relative_residual(const Evaluation& at, double t,
                                       const NewtonPolicy& policy) const
{
  const double supports =
      policy.support_force_n ? *policy.support_force_n : reaction_norm(at.gradient);
  return at.free_gradient.norm() / std::max({(t * m_external).norm(), supports, m_force_floor});
}

std::string NewtonEngine::describe_inversion(const BodyEnergy& energy) const
{
  if (energy.first_inverted < 0)
    return "a node would cross a contact surface";
  return fmt::format("element {} inverts (J = {:.3g})", energy.first_inverted, energy.inverted_j);
}

int NewtonEngine::prepare(const Eigen::VectorXd& x, bool project,
                          const std::vector<NodeBlock>& blocks, const Eigen::VectorXd& shift,
                          Evaluation* body)
{
  // Pi's Hessian: K (1 + c, the damping's K_s taken as K) + blocks + inertia weights + shift.
  const double damping = m_damping ? m_damping->factor : 0.0;
  Eigen::VectorXd diagonal = shift;
  if (m_inertia)
    diagonal =
        diagonal.size() == 0 ? m_inertia->weight : Eigen::VectorXd(diagonal + m_inertia->weight);
  return body ? m_linear.prepare(x, project, 1.0 + damping, diagonal, blocks, &body->body,
                                 &body->gradient)
              : m_linear.prepare(x, project, 1.0 + damping, diagonal, blocks);
}

bool NewtonEngine::direction(const Eigen::VectorXd& x, double t, const Eigen::VectorXd& rhs,
                             const NewtonPolicy& policy, int iteration, Eigen::VectorXd& direction,
                             NewtonCounts& counts, bool allow_saddle, bool& saddle)
{
  saddle = false;
  if (m_shifted)
    return shifted_direction(x, t, rhs, direction, counts);
  bool project = m_projection == PsdProjection::always;
  // The extra potential's exact Hessian first: a contact barrier's projected Hessian drops the
  // obstacle's curvature, and Newton converges only linearly on nodes that slide over it.
  bool exact_extra = m_extra && !project && iteration >= policy.exact_extra_from;
  std::vector<NodeBlock> blocks;
  if (m_prepared)
    blocks.swap(m_prepared->blocks);
  else if (m_extra)
    m_extra->hessian_blocks(x, t, !exact_extra, blocks);
  for (;;) {
    if (m_prepared)
      counts.projected_elements += m_prepared->projected_elements;
    else
      counts.projected_elements += prepare(x, project, blocks);
    m_prepared.reset();
    direction = Eigen::VectorXd::Zero(rhs.size());
    const LinearSolveReport solve = m_linear.solve(rhs, direction);
    counts.linear_iterations += solve.iterations;
    counts.factorizations += solve.factorizations;
    // A Newton step must go downhill in energy: rhs is minus the gradient.
    const bool downhill = solve.ok && direction.allFinite() && direction.dot(rhs) > 0.0;
    if (downhill)
      return true;
    if (exact_extra && (solve.indefinite || solve.ok)) {
      if (policy.indefinite_exact_extra_fails && iteration > 0 && solve.indefinite) {
        m_failure = "the system matrix is indefinite";
        return false;
      }
      // Indefinite with the exact extra Hessian: its projection next, then the elements'.
      exact_extra = false;
      blocks.clear();
      m_extra->hessian_blocks(x, t, true, blocks);
      continue;
    }
    if (!project && m_projection == PsdProjection::automatic && (solve.indefinite || solve.ok)) {
      ++counts.indefinite_iterations;
      // The unprojected Newton step converges quadratically to a saddle equilibrium (a state
      // past a bifurcation), where the projected one crawls or walks away from it.
      // The factorised tangent is the body's alone: no saddle step with an extra potential or
      // an incremental potential.
      const bool may_saddle =
          allow_saddle && policy.saddle_steps && m_tangent && !m_extra && !m_inertia && !m_damping;
      const int factorizations_before = m_tangent ? m_tangent->factorizations() : 0;
      const bool factorized = may_saddle && m_tangent->factorize(x);
      if (m_tangent)
        counts.factorizations += m_tangent->factorizations() - factorizations_before;
      if (factorized) {
        direction = m_tangent->solve(rhs);
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

bool NewtonEngine::shifted_direction(const Eigen::VectorXd& x, double t, const Eigen::VectorXd& rhs,
                                     Eigen::VectorXd& direction, NewtonCounts& counts)
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
    prepare(x, false, blocks, shift > 0.0 ? Eigen::VectorXd(shift * unit) : Eigen::VectorXd());
    direction = Eigen::VectorXd::Zero(rhs.size());
    const LinearSolveReport solve = m_linear.solve(rhs, direction);
    counts.linear_iterations += solve.iterations;
    counts.factorizations += solve.factorizations;
    if (solve.ok && direction.allFinite() && direction.dot(rhs) > 0.0) {
      if (shift > 0.0) {
        ++counts.shifted_iterations;
        m_shift = shift;
      }
      return true;
    }
    if (shift == 0.0)
      ++counts.indefinite_iterations;
    shift = shift == 0.0 ? std::max(first_shift, m_shift / 3.0) : 10.0 * shift;
    if (shift > largest_shift) {
      m_failure = fmt::format("no shifted Newton step up to {:.0e} D goes downhill", largest_shift);
      return false;
    }
  }
}

double NewtonEngine::energy_scale(const Eigen::VectorXd& x, const Evaluation& at, double t) const
{
  // Round-off in the element sum scales with the material's energy per volume, even where
  // the strain energy itself is near zero (rigid motions).
  return std::abs(at.body.energy) + std::abs(t * m_external.dot(x - m_rest)) + m_energy_unit;
}

bool NewtonEngine::line_search(const Eigen::VectorXd& x, const Evaluation& current,
                               const Eigen::VectorXd& direction, bool saddle, double t,
                               const NewtonPolicy& policy, NewtonCounts& counts,
                               Eigen::VectorXd& x_trial, Evaluation& trial, double& alpha)
{
  const Eigen::VectorXd& residual = current.free_gradient;
  const double slope = residual.dot(direction); // < 0 for an energy step
  auto step_to = [&](double a) {
    x_trial = x;
    m_dofs.scatter_add(direction, a, x_trial);
    evaluate(x_trial, t, trial);
  };
  // An extra potential bounds the step: no node crosses a contact surface on the way.
  alpha = m_extra ? std::clamp(m_extra->max_step(x, m_dofs.expand(direction), t), 0.0, 1.0) : 1.0;
  if (saddle) {
    // The Newton step decreases |r|^2 at the rate 2 |r|^2 whatever the inertia of K.
    const double norm = residual.norm();
    for (int k = 0; k < max_residual_search_steps; ++k, alpha *= 0.5) {
      step_to(alpha);
      if (std::isfinite(trial.total_energy) &&
          trial.free_gradient.norm() <= (1.0 - armijo * alpha) * norm)
        return true;
      ++counts.line_search_backtracks;
    }
    return false;
  }
  if (!policy.energy_decrease) {
    // Any admissible fraction: the largest of alpha, alpha / 2, ...
    for (int k = 0;; ++k, alpha *= 0.5) {
      step_to(alpha);
      if (std::isfinite(trial.total_energy))
        return true;
      if (k == policy.admissible_backtracks) {
        m_failure = fmt::format("the step: {}", trial.extra_inadmissible
                                                    ? "a node would cross a contact surface"
                                                    : describe_inversion(trial.body));
        return false;
      }
      ++counts.line_search_backtracks;
    }
  }

  // Backtracking line search on Pi.
  const double scale = energy_scale(x, current, t);
  BodyEnergy last_inversion;
  for (int k = 0; k < max_line_search_steps; ++k) {
    step_to(alpha);
    if (std::isfinite(trial.total_energy) && alpha > 0.0) {
      const double change = trial.total_energy - current.total_energy;
      if (change <= armijo * alpha * slope)
        return true;
      if (std::abs(change) <= energy_round_off * scale &&
          trial.free_gradient.norm() < residual.norm())
        return true; // the energy is flat to round-off: accept a smaller residual
      // Minimiser of the quadratic through E(0), E'(0) and E(alpha), kept in [0.1, 0.5] alpha.
      const double curvature = change - alpha * slope;
      const double next = curvature > 0.0 ? -slope * alpha * alpha / (2.0 * curvature) : 0.5;
      alpha = std::clamp(next, 0.1 * alpha, 0.5 * alpha);
    } else {
      last_inversion = trial.body;
      alpha *= 0.5;
    }
    ++counts.line_search_backtracks;
  }
  m_failure = last_inversion.first_inverted >= 0
                  ? fmt::format("the line search found no admissible step: {}",
                                describe_inversion(last_inversion))
                  : "the line search found no energy decrease";
  return false;
}

NewtonOutcome NewtonEngine::minimise(Eigen::VectorXd& x, double t, const NewtonPolicy& policy,
                                     NewtonCounts& counts, std::optional<Evaluation>& current)
{
  m_prepared.reset();
  if (!current && policy.min_iterations > 0 && !m_shifted) {
    // The first iteration needs the matrix at x: one pass over the elements gives it with the
    // energy and the gradient, and direction() takes it as it is.
    current.emplace();
    m_prepared.emplace();
    const bool project = m_projection == PsdProjection::always;
    if (m_extra)
      m_extra->hessian_blocks(x, t, project || policy.exact_extra_from > 0, m_prepared->blocks);
    m_prepared->projected_elements = prepare(x, project, m_prepared->blocks, {}, &*current);
    complete(x, t, *current);
    if (!std::isfinite(current->body.energy))
      m_prepared.reset();
  }
  if (!current) {
    current.emplace();
    evaluate(x, t, *current);
  }
  if (!std::isfinite(current->body.energy)) {
    m_failure = describe_inversion(current->body);
    return NewtonOutcome::failed;
  }
  if (current->extra_inadmissible) {
    m_failure = "a node lies inside a contact obstacle, too deep to be moved out (beyond the "
                "obstacle's distance band)";
    return NewtonOutcome::failed;
  }
  NewtonConvergence convergence(policy.residual_tolerance, policy.energy_tolerance, m_length_mm);
  const int max_iterations = (m_shifted ? shifted_iteration_factor : 1) * policy.max_iterations;
  for (int iteration = 0;; ++iteration) {
    const Eigen::VectorXd& residual = current->free_gradient;
    if (!residual.allFinite()) {
      m_failure = "the internal forces are not finite";
      return NewtonOutcome::failed;
    }
    counts.relative_residual = relative_residual(*current, t, policy);
    if (iteration >= policy.min_iterations) {
      const ConvergenceVerdict verdict =
          convergence.verdict(counts.relative_residual, residual.norm() <= m_force_floor);
      if (verdict == ConvergenceVerdict::converged_at_floor) {
        counts.converged_at_floor = true;
        counts.floor = convergence.floor_summary();
      }
      if (verdict != ConvergenceVerdict::iterate)
        return NewtonOutcome::converged;
    }
    if (iteration == max_iterations) {
      m_failure = fmt::format("no convergence in {} Newton iterations (relative residual {:.3g})",
                              iteration, counts.relative_residual);
      if (counts.indefinite_iterations > 0)
        m_failure += fmt::format("; the stiffness matrix was indefinite in {} iterations",
                                 counts.indefinite_iterations);
      return NewtonOutcome::out_of_iterations;
    }
    ++counts.iterations;

    Eigen::VectorXd step;
    Eigen::VectorXd x_trial;
    Evaluation trial;
    double alpha = 1.0;
    bool saddle = false;
    if (!direction(x, t, -residual, policy, iteration, step, counts, true, saddle))
      return NewtonOutcome::failed;
    bool moved = line_search(x, *current, step, saddle, t, policy, counts, x_trial, trial, alpha);
    if (saddle && !moved) {
      // The unprojected step made no progress on the residual: minimise the energy instead.
      if (!direction(x, t, -residual, policy, iteration, step, counts, false, saddle))
        return NewtonOutcome::failed;
      moved = line_search(x, *current, step, false, t, policy, counts, x_trial, trial, alpha);
    }
    const double round_off = energy_round_off * energy_scale(x, *current, t);
    IterationFigures figures;
    figures.displacement_step_mm = step.lpNorm<Eigen::Infinity>();
    figures.energy_round_off = round_off;
    if (!moved) {
      // At the round-off floor the energy cannot tell a better state from a worse one: when the
      // whole step would change it by less than round-off and no trial lowered the residual,
      // the iteration stagnates where it is (and the convergence test sees the floor).
      if (saddle || !policy.energy_decrease ||
          counts.relative_residual > NewtonConvergence::max_floor ||
          std::abs(residual.dot(step)) > round_off)
        return NewtonOutcome::failed;
      if (policy.verbose)
        log_info(fmt::format("load {:.4g} iteration {}: relative residual {:.3e}, no step "
                             "changes the energy beyond round-off (stagnating)",
                             t, iteration + 1, counts.relative_residual));
      figures.relative_residual = counts.relative_residual;
      convergence.record(figures);
      continue;
    }
    counts.saddle_iterations += saddle ? 1 : 0;
    if (policy.verbose)
      log_info(fmt::format("load {:.4g} iteration {}: relative residual {:.3e}, step {:.3g}{} "
                           "({} projected elements, {} factorisations, {} CG iterations so far)",
                           t, iteration + 1, counts.relative_residual, alpha,
                           saddle ? " (indefinite Newton)" : "", counts.projected_elements,
                           counts.factorizations, counts.linear_iterations));
    figures.energy_change = std::abs(alpha * residual.dot(step));
    x.swap(x_trial);
    std::swap(*current, trial);
    figures.relative_residual = relative_residual(*current, t, policy);
    convergence.record(figures);
  }
}

} // namespace ligsim::sim
