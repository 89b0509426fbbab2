#include "sim/solver/implicit_euler.hpp"

#include "common/error.hpp"
#include "common/resources.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace ligsim::sim {

namespace {

/// kg/m^3 to t/mm^3, the mass unit consistent with mm, N and s.
constexpr double kg_per_m3_to_t_per_mm3 = 1e-12;

/// Halvings of a Newton move that would invert an element before the step fails.
constexpr int max_backtracks = 10;

} // namespace

ImplicitEuler::ImplicitEuler(const HyperelasticBody& body, const BoundaryConditions& conditions,
                             const DynamicsSettings& settings)
    : m_body(body)
    , m_conditions(conditions)
    , m_settings(settings)
    , m_dofs(body.node_count(), conditions, body.unreferenced_nodes())
    , m_external(m_dofs.external_forces(conditions))
    , m_linear(body, m_dofs, settings.linear_solver, settings.pcg)
    , m_engine(body, m_dofs, m_external, m_linear, nullptr, settings.projection)
{
  if (!(settings.time_step_s > 0.0) || !std::isfinite(settings.time_step_s))
    fail("dynamics: time_step_s must be positive, got {}", settings.time_step_s);
  if (settings.frames < 1)
    fail("dynamics: frames must be at least 1, got {}", settings.frames);
  if (settings.ramp_frames < 1)
    fail("dynamics: ramp_frames must be at least 1, got {}", settings.ramp_frames);
  if (!(settings.density_kg_m3 > 0.0))
    fail("dynamics: density_kg_m3 must be positive, got {}", settings.density_kg_m3);
  if (settings.mass_damping_per_s < 0.0 || settings.stiffness_damping_s < 0.0)
    fail("dynamics: damping coefficients must not be negative");
  if (settings.max_iterations < 1)
    fail("dynamics: max_iterations must be at least 1, got {}", settings.max_iterations);
  if (!(settings.iteration_tolerance > 0.0))
    fail("dynamics: iteration_tolerance must be positive, got {}", settings.iteration_tolerance);
  if (m_dofs.free_count() == 0)
    fail("every degree of freedom is prescribed: nothing to solve");

  const double density = settings.density_kg_m3 * kg_per_m3_to_t_per_mm3;
  m_mass = Eigen::VectorXd::Zero(body.dof_count());
  // Quadratic tets have no positive row-sum lumped mass (their corners' rows sum to a
  // negative mass); the interactive mode, the one user of dynamics, runs linear tets.
  if (body.quadratic())
    fail("dynamics takes linear tets; this body has quadratic ones");
  const ElementNodes& T = body.elements();
  for (Eigen::Index e = 0; e < T.rows(); ++e)
    for (int i = 0; i < 4; ++i)
      m_mass.segment<3>(3 * T(e, i)).array() += density * body.element_volume(e) / 4.0;
  m_free_mass = m_dofs.gather(m_mass);

  if (settings.stiffness_damping_s > 0.0) {
    m_damping_stiffness = std::make_unique<StiffnessMatrix>(T, m_dofs);
    m_damping.K_s = &m_damping_stiffness->matrix();
  }
}

void ImplicitEuler::set_extra_potential(const ExtraPotential* potential)
{
  m_engine.set_extra_potential(potential);
}

bool ImplicitEuler::step(Eigen::VectorXd& x, Eigen::VectorXd& v, double h, double t,
                         FrameReport& report)
{
  // Prescribed DOFs jump to their targets; the step starts there with the free nodes unmoved.
  m_dofs.apply_targets(m_conditions, m_body.mesh().V, t, x);
  if (const ExtraPotential* extra = m_engine.extra_potential())
    extra->make_admissible(x, t);

  // The step minimises (1 + h alpha) / (2 h^2) |x - x_s - h v_s / (1 + h alpha)|_M^2 + W(x) -
  // t f.x + extra + beta / (2 h) (x - x_s)^T K_s (x - x_s): its stationarity is implicit
  // Euler's M (v - v_s) = h f(x) - h alpha M v - h beta K_s v with x = x_s + h v, and Newton's
  // first iteration from x_s is Baraff and Witkin's linearised solve.
  const double alpha = m_settings.mass_damping_per_s;
  const double beta = m_settings.stiffness_damping_s;
  const Eigen::VectorXd start = m_dofs.gather(x);
  m_inertia.weight = (1.0 + h * alpha) / (h * h) * m_free_mass;
  m_inertia.target = start + h / (1.0 + h * alpha) * m_dofs.gather(v);
  if (beta > 0.0) {
    if (!std::isfinite(m_body.energy(x).energy)) {
      m_failure = "moving the prescribed nodes inverts an element";
      return false;
    }
    // K_s projected: a dissipation potential must not release energy.
    m_damping_stiffness->set_zero();
    m_damping_stiffness->add_elements(m_body, x, true);
    m_damping.factor = beta / h;
    m_damping.start = start;
  }
  m_engine.set_incremental_terms(&m_inertia, beta > 0.0 ? &m_damping : nullptr);

  NewtonPolicy policy;
  policy.max_iterations = m_settings.max_iterations;
  policy.min_iterations = 1; // Baraff and Witkin's solve, whatever the state's residual
  policy.residual_tolerance = m_settings.iteration_tolerance;
  policy.energy_tolerance = NewtonConvergence::no_energy_test;
  policy.support_force_n = m_support_force;
  policy.saddle_steps = false;
  // The contact's exact Hessian blocks in Newton's later iterations (their projection drops the
  // bone's curvature and makes Newton linear on sliding nodes), projected in the first solve;
  // indefinite with them, a shorter sub-step (the mass part grows against K) is cheaper than
  // Newton with projected blocks; the last halving projects.
  policy.exact_extra_from = 1;
  policy.indefinite_exact_extra_fails = !m_last_halving;
  // Implicit Euler takes its solves' steps whole where they are admissible; with Newton
  // iterations to come, a move that would invert an element is halved instead (with one
  // solve, the time step is).
  policy.energy_decrease = false;
  policy.admissible_backtracks = m_settings.max_iterations == 1 ? 0 : max_backtracks;

  NewtonCounts counts;
  std::optional<NewtonEngine::Evaluation> current;
  const NewtonOutcome outcome = m_engine.minimise(x, t, policy, counts, current);
  report.add(counts);
  if (outcome == NewtonOutcome::failed) {
    m_failure = counts.iterations == 0 && !std::isfinite(current->body.energy)
                    ? "moving the prescribed nodes: " + m_engine.failure()
                    : m_engine.failure();
    return false;
  }
  m_step_met = outcome == NewtonOutcome::converged || m_settings.max_iterations == 1;
  m_dofs.scatter((m_dofs.gather(x) - start) / h, v);
  m_end = std::move(current);
  return true;
}

double ImplicitEuler::support_force(const Eigen::VectorXd& x) const
{
  Eigen::VectorXd gradient;
  if (!std::isfinite(m_body.energy_gradient(x, gradient).energy))
    return 0.0;
  return m_engine.reaction_norm(gradient);
}

void ImplicitEuler::start(const Eigen::VectorXd& x)
{
  m_support_force = support_force(x);
}

bool ImplicitEuler::frame(Eigen::VectorXd& x, Eigen::VectorXd& v, double t_before,
                          FrameReport& report, Eigen::VectorXd& residual)
{
  const auto frame_start = std::chrono::steady_clock::now();
  const double h = m_settings.time_step_s;
  // The frame in 2^k equal sub-steps; k grows when a sub-step fails.
  const Eigen::VectorXd x_saved = x;
  const Eigen::VectorXd v_saved = v;
  bool done = false;
  for (int halvings = 0; halvings <= m_settings.max_halvings && !done; ++halvings) {
    const int substeps = 1 << halvings;
    m_last_halving = halvings == m_settings.max_halvings;
    x = x_saved;
    v = v_saved;
    done = true;
    report.equation_met = true;
    for (int s = 1; s <= substeps && done; ++s) {
      const double t = t_before + (report.load_factor - t_before) * s / substeps;
      done = step(x, v, h / substeps, t, report);
      report.equation_met = report.equation_met && m_step_met;
    }
    report.substeps = substeps;
  }
  if (!done) {
    x = x_saved;
    v = v_saved;
    m_failure = fmt::format("failed after {} halvings of the time step: {}",
                            m_settings.max_halvings, m_failure);
    return false;
  }

  report.strain_energy_mj = m_end->body.energy;
  residual = m_end->gradient;
  double residual2 = 0.0;
  double reaction2 = 0.0;
  double inertia2 = 0.0;
  for (int dof = 0; dof < m_dofs.dof_count(); ++dof) {
    if (m_dofs.is_free(dof)) {
      residual2 += residual(dof) * residual(dof);
      inertia2 += std::pow(m_mass(dof) * v(dof) / h, 2);
    } else {
      reaction2 += residual(dof) * residual(dof);
    }
  }
  m_support_force = std::sqrt(reaction2);
  const double scale = std::max(
      {(report.load_factor * m_external).norm(), std::sqrt(reaction2), m_engine.force_floor()});
  report.relative_residual = std::sqrt(residual2) / scale;
  report.relative_inertia = std::sqrt(inertia2) / scale;
  report.kinetic_energy_mj = 0.5 * v.dot(m_mass.cwiseProduct(v));
  std::tie(report.min_j, report.min_j_element) = m_body.min_j(x);
  report.wall_s = seconds_since(frame_start);
  return true;
}

DynamicResult ImplicitEuler::run(Eigen::VectorXd& x, const FrameCallback& on_frame)
{
  const auto start_time = std::chrono::steady_clock::now();
  DynamicResult result;
  if (!valid_start(x, m_dofs.dof_count(), result.failure))
    return result;
  Eigen::VectorXd v = Eigen::VectorXd::Zero(x.size());
  const double h = m_settings.time_step_s;
  start(x);
  Eigen::VectorXd residual;
  for (int frame_number = 1; frame_number <= m_settings.frames; ++frame_number) {
    FrameReport report;
    report.frame = frame_number;
    report.time_s = frame_number * h;
    const double t_before =
        std::min(1.0, static_cast<double>(frame_number - 1) / m_settings.ramp_frames);
    report.load_factor = std::min(1.0, static_cast<double>(frame_number) / m_settings.ramp_frames);
    const bool done = frame(x, v, t_before, report, residual);
    result.substeps += report.substeps;
    result.add(report);
    if (!done) {
      result.failure = fmt::format("frame {} {}", frame_number, m_failure);
      result.wall_s = seconds_since(start_time);
      return result;
    }
    result.frames = frame_number;
    if (on_frame)
      on_frame(report, x, residual);
    const bool at_rest = report.load_factor >= 1.0 &&
                         report.relative_residual <= m_settings.convergence_tolerance &&
                         report.relative_inertia <= m_settings.convergence_tolerance;
    if (at_rest)
      result.reached_equilibrium = true;
    if (at_rest && m_settings.until_converged)
      break;
  }
  result.completed = !m_settings.until_converged || result.reached_equilibrium;
  if (!result.completed)
    result.failure = fmt::format("not at rest after {} frames (relative residual above {:.3g})",
                                 result.frames, m_settings.convergence_tolerance);
  result.wall_s = seconds_since(start_time);
  return result;
}

} // namespace ligsim::sim
