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

StaticSolver::StaticSolver(const HyperelasticBody& body, const BoundaryConditions& conditions,
                           const NewtonSettings& settings)
    : m_body(body)
    , m_conditions(conditions)
    , m_settings(settings)
    , m_dofs(body.node_count(), conditions, body.unreferenced_nodes())
    , m_external(m_dofs.external_forces(conditions))
    , m_linear(body, m_dofs, settings.linear_solver, settings.pcg)
    , m_tangent(body, m_dofs, m_linear.direct())
    , m_engine(body, m_dofs, m_external, m_linear, &m_tangent, settings.projection)
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
  m_policy.max_iterations = settings.max_iterations;
  m_policy.residual_tolerance = settings.residual_tolerance;
  m_policy.energy_tolerance = settings.energy_tolerance;
  m_policy.verbose = settings.verbose;
  const ElementNodes& T = body.elements();
  for (Eigen::Index e = 0; e < T.rows(); ++e)
    for (Eigen::Index i = 0; i < T.cols(); ++i)
      if (!m_dofs.is_free(3 * T(e, i)) || !m_dofs.is_free(3 * T(e, i) + 1) ||
          !m_dofs.is_free(3 * T(e, i) + 2)) {
        m_boundary_elements.push_back(static_cast<int>(e));
        break;
      }
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
  const ExtraPotential* extra = m_engine.extra_potential();
  NewtonEngine::Evaluation at;
  m_engine.evaluate(x, extra ? m_converged_t : t1, at);
  if (!std::isfinite(at.body.energy)) {
    // No stiffness to predict with (an inverted element has none): a caller's guess of the
    // start that cannot be a state.
    m_failure = fmt::format("moving the prescribed nodes to load factor {:.4g}: the state they "
                            "move from is not admissible ({})",
                            t1, m_engine.describe_inversion(at.body));
    return false;
  }
  if (extra)
    at.gradient -= (t1 - m_converged_t) * m_external;
  const Eigen::VectorXd coupling = m_body.apply_stiffness(x, shift, &m_boundary_elements);
  const Eigen::VectorXd rhs = -m_dofs.gather(at.gradient + coupling);
  Eigen::VectorXd predictor;
  bool saddle = false;
  if (!m_engine.direction(x, m_converged_t, rhs, m_policy, 0, predictor, report, true, saddle))
    predictor = Eigen::VectorXd::Zero(rhs.size()); // the prescribed move alone, checked below

  BodyEnergy energy;
  for (double alpha = 1.0; alpha > 1e-3; alpha *= 0.5) {
    Eigen::VectorXd trial = target;
    m_dofs.scatter_add(predictor, alpha, trial);
    if (extra)
      extra->make_admissible(trial, t1);
    energy = m_body.energy(trial);
    if (extra && std::isfinite(energy.energy) && !std::isfinite(extra->energy(trial, t1, nullptr)))
      energy = BodyEnergy{INFINITY, -1, 1.0};
    if (std::isfinite(energy.energy)) {
      x = trial;
      return true;
    }
  }
  m_failure = fmt::format("moving the prescribed nodes to load factor {:.4g}: {}", t1,
                          m_engine.describe_inversion(energy));
  return false;
}

bool StaticSolver::advance(Eigen::VectorXd& x, double t1, StepReport& report)
{
  if (m_dofs.has_moving_targets() && !move_prescribed(x, t1, report))
    return false;
  const ExtraPotential* extra = m_engine.extra_potential();
  const int pushed = extra ? extra->make_admissible(x, t1) : 0;
  std::optional<NewtonEngine::Evaluation> current;
  const NewtonOutcome outcome = m_engine.minimise(x, t1, m_policy, report, current);
  if (outcome == NewtonOutcome::converged) {
    m_converged_t = t1;
    return true;
  }
  m_failure = m_engine.failure();
  if (pushed > 0 && !std::isfinite(current->body.energy))
    m_failure = fmt::format("moving {} nodes out of a contact obstacle: {} (they started too "
                            "deep inside it)",
                            pushed, m_failure);
  return false;
}

StaticResult StaticSolver::solve(Eigen::VectorXd& x, const StepCallback& on_step)
{
  const auto start = std::chrono::steady_clock::now();
  StaticResult result;
  if (!valid_start(x, m_dofs.dof_count(), result.failure))
    return result;
  const std::vector<double> targets = step_targets();
  const int steps = static_cast<int>(targets.size());
  m_engine.set_shifted(false); // a solve that failed before may have left it on
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
      m_engine.set_failure("");
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
      if (!m_engine.shifted() && m_engine.extra_potential() &&
          m_settings.projection == PsdProjection::automatic &&
          report.indefinite_iterations > indefinite_before) {
        // With an extra potential there is no saddle step, and the projected one crawls along
        // a buckling mode: the same sub-step again, with shifted Newton steps.
        m_engine.set_shifted(true);
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
        result.add(report);
        result.wall_s = seconds_since(start);
        return result;
      }
    }
    report.converged = true;
    report.load_factor = t_end;
    m_engine.set_shifted(false);
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
    if (const ExtraPotential* extra = m_engine.extra_potential())
      extra->energy(x, t_end, &gradient);
    std::tie(report.min_j, report.min_j_element) = m_body.min_j(x);
    report.wall_s = seconds_since(step_start);
    result.add(report);
    result.steps.push_back(report);
    if (on_step)
      on_step(report, x, gradient);
  }
  result.converged = true;
  result.wall_s = seconds_since(start);
  return result;
}

} // namespace ligsim::sim
