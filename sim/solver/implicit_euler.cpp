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
  const Tetrahedra& T = body.mesh().T;
  for (Eigen::Index e = 0; e < T.rows(); ++e)
    for (int i = 0; i < 4; ++i)
      m_mass.segment<3>(3 * T(e, i)).array() += density * body.shape(e).V0 / 4.0;
  m_free_mass = m_dofs.gather(m_mass);

  const Points& V = body.mesh().V;
  const double size = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  m_force_floor = 1e-12 * body.material().parameters().mu_mpa * size * size;
}

bool ImplicitEuler::step(Eigen::VectorXd& x, Eigen::VectorXd& v, double h, double t,
                         FrameReport& report)
{
  const double alpha = m_settings.mass_damping_per_s;
  const double beta = m_settings.stiffness_damping_s;

  // Prescribed DOFs jump to their targets; the solve sees them as already moved.
  m_dofs.apply_targets(m_conditions, m_body.mesh().V, t, x);
  if (m_extra)
    m_extra->make_admissible(x, t);

  // With A = M (1 + h alpha) + (h^2 + h beta) K, the first solve linearises at the step's start
  // (free nodes not yet moved by h v):
  //   A dv = h f - h (h + beta) K v - h alpha M v = h f - (A v - M v);
  // later ones are Newton on the same equation at x = x_start + h v:
  //   A dv = h f - M (1 + h alpha) v + M v_start - h beta K v.
  const Eigen::VectorXd mass_term = (1.0 + h * alpha) * m_free_mass;
  const double stiffness_scale = h * h + h * beta;
  bool project = m_settings.projection == PsdProjection::always;
  const Eigen::VectorXd start_velocity = m_dofs.gather(v);
  Eigen::VectorXd velocity = start_velocity;
  m_step_met = false;
  for (int iteration = 0; iteration < m_settings.max_iterations; ++iteration) {
    // The contact's exact Hessian blocks in Newton's iterations (their projection drops the
    // bone's curvature and makes Newton linear on sliding nodes), projected in the first solve
    // and wherever the matrix is indefinite with them.
    std::vector<NodeBlock> blocks;
    if (m_extra)
      m_extra->hessian_blocks(x, t, iteration == 0 || project, blocks);
    // The matrix's pass over the elements gives the body's energy and gradient too.
    BodyEnergy energy;
    Eigen::VectorXd gradient;
    report.projected_elements +=
        m_linear.prepare(x, project, stiffness_scale, mass_term, blocks, &energy, &gradient);
    if (!std::isfinite(energy.energy)) {
      m_failure = fmt::format("{} inverts element {} (J = {:.3g})",
                              iteration == 0 ? "moving the prescribed nodes" : "the step",
                              energy.first_inverted, energy.inverted_j);
      return false;
    }
    gradient -= t * m_external;
    if (m_extra && !std::isfinite(m_extra->energy(x, t, &gradient))) {
      m_failure = "a node lies inside a contact obstacle and could not be moved out";
      return false;
    }
    const Eigen::VectorXd force = -m_dofs.gather(gradient);

    Eigen::VectorXd dv;
    for (bool prepared = true;; prepared = false) {
      if (!prepared) {
        blocks.clear(); // the exact blocks out, their projections in
        if (m_extra)
          m_extra->hessian_blocks(x, t, true, blocks);
        report.projected_elements +=
            m_linear.prepare(x, project, stiffness_scale, mass_term, blocks);
      }
      Eigen::VectorXd Av;
      m_linear.multiply(velocity, Av);
      Eigen::VectorXd rhs;
      if (iteration == 0) {
        rhs = h * force - Av + m_free_mass.cwiseProduct(velocity);
      } else {
        rhs =
            h * force - mass_term.cwiseProduct(velocity) + m_free_mass.cwiseProduct(start_velocity);
        if (beta > 0.0) // h beta K v, with K v from A v
          rhs -= (h * beta / stiffness_scale) * (Av - mass_term.cwiseProduct(velocity));
      }
      dv = Eigen::VectorXd::Zero(rhs.size());
      const LinearSolveReport solve = m_linear.solve(rhs, dv);
      report.linear_iterations += solve.iterations;
      report.factorizations += solve.factorizations;
      if (solve.ok && dv.allFinite())
        break;
      // Newton's later solves carry the contact's exact blocks: indefinite with them, a shorter
      // sub-step (A's mass part grows against h^2 K) is cheaper than Newton with projected
      // blocks, which converges only linearly on sliding nodes; the last halving projects.
      if (solve.indefinite && iteration > 0 && !m_last_halving) {
        m_failure = "the system matrix is indefinite";
        return false;
      }
      if (solve.indefinite && !project && m_settings.projection == PsdProjection::automatic) {
        project = true;
        continue;
      }
      m_failure = solve.indefinite
                      ? "the system matrix is indefinite"
                      : fmt::format("the linear solver did not converge (relative residual {:.3g})",
                                    solve.relative_residual);
      return false;
    }
    // The move (h (v + dv) from the step's start, h dv after it) stops short of any contact
    // surface; the velocity change shrinks with it.
    const Eigen::VectorXd move = h * (iteration == 0 ? Eigen::VectorXd(velocity + dv) : dv);
    double fraction = 1.0;
    if (m_extra)
      fraction = std::clamp(m_extra->max_step(x, m_dofs.expand(move), t), 0.0, 1.0);
    // The state's energy and gradient: the step's result if it is done, which it is when the
    // move went all the way and the step's equation holds to `iteration_tolerance` of the
    // supports' force; else Newton goes on from here. With Newton iterations to come, a move
    // that would invert an element is halved instead (with one solve, the time step is).
    const Eigen::VectorXd x_before = x;
    BodyEnergy after;
    for (int backtrack = 0;; ++backtrack) {
      x = x_before;
      m_dofs.scatter_add(move, fraction, x);
      after = m_body.energy_gradient(x, m_end_gradient);
      if (std::isfinite(after.energy) || m_settings.max_iterations == 1 ||
          backtrack == max_backtracks)
        break;
      fraction *= 0.5;
    }
    m_end_energy = after.energy;
    if (!std::isfinite(after.energy)) {
      m_failure = fmt::format("the step inverts element {} (J = {:.3g})", after.first_inverted,
                              after.inverted_j);
      return false;
    }
    velocity = iteration == 0 ? Eigen::VectorXd(fraction * (velocity + dv))
                              : Eigen::VectorXd(velocity + fraction * dv);
    if (fraction >= 1.0 && converged(x, h, t, velocity, start_velocity, mass_term)) {
      m_step_met = true;
      break;
    }
  }
  m_dofs.scatter(velocity, v);
  if (m_extra && !std::isfinite(m_extra->energy(x, t, nullptr))) {
    m_failure = "the step would move a node across a contact surface";
    return false;
  }
  return true;
}

bool ImplicitEuler::converged(const Eigen::VectorXd& x, double h, double t,
                              const Eigen::VectorXd& velocity,
                              const Eigen::VectorXd& start_velocity,
                              const Eigen::VectorXd& mass_term) const
{
  if (m_settings.max_iterations <= 1)
    return true;
  Eigen::VectorXd gradient = m_end_gradient - t * m_external;
  if (m_extra && !std::isfinite(m_extra->energy(x, t, &gradient)))
    return true; // the caller reports it
  // The equation's residual h f - M (1 + h alpha) v + M v_start (the stiffness damping's
  // h beta K v left out: it needs the matrix) against h times the supports' force at the last
  // accepted frame (not this state's, which a wrong state inflates).
  const Eigen::VectorXd free_gradient = m_dofs.gather(gradient);
  double residual2 = 0.0;
  for (Eigen::Index i = 0; i < free_gradient.size(); ++i) {
    const double r =
        -h * free_gradient(i) - mass_term(i) * velocity(i) + m_free_mass(i) * start_velocity(i);
    residual2 += r * r;
  }
  const double scale = h * std::max({(t * m_external).norm(), m_support_force, m_force_floor});
  return std::sqrt(residual2) <= m_settings.iteration_tolerance * scale;
}

double ImplicitEuler::support_force(const Eigen::VectorXd& x) const
{
  Eigen::VectorXd gradient;
  if (!std::isfinite(m_body.energy_gradient(x, gradient).energy))
    return 0.0;
  double reaction2 = 0.0;
  for (int dof = 0; dof < m_dofs.dof_count(); ++dof)
    if (!m_dofs.is_free(dof))
      reaction2 += gradient(dof) * gradient(dof);
  return std::sqrt(reaction2);
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

  report.strain_energy_mj = m_end_energy;
  residual = m_end_gradient;
  residual -= report.load_factor * m_external;
  if (m_extra)
    m_extra->energy(x, report.load_factor, &residual);
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
  const double scale =
      std::max({(report.load_factor * m_external).norm(), std::sqrt(reaction2), m_force_floor});
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
  if (x.size() != m_dofs.dof_count() || !x.allFinite()) {
    result.failure = "the initial positions are missing or not finite";
    return result;
  }
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
    result.linear_iterations += report.linear_iterations;
    result.factorizations += report.factorizations;
    result.projected_elements += report.projected_elements;
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
