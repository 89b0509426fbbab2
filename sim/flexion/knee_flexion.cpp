#include "sim/flexion/knee_flexion.hpp"

#include "common/error.hpp"
#include "common/progress.hpp"
#include "common/resources.hpp"
#include "common/run_summary.hpp"
#include "sim/solver/implicit_euler.hpp"
#include "sim/solver/static_solver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace ligsim::sim {

namespace {

constexpr double degree = M_PI / 180.0;

/// Index of the constraint set called `name`, or -1.
int set_index(const BoundaryConditions& conditions, const std::string& name)
{
  for (std::size_t s = 0; s < conditions.constraints.size(); ++s)
    if (conditions.constraints[s].name == name)
      return static_cast<int>(s);
  return -1;
}

/// Energy, fiber stretch, attachment forces and contact of state `x` at load factor t.
void measure(const HyperelasticBody& body, const BoundaryConditions& conditions,
             const KneeContact* contact, bool contact_on, double t, const Eigen::VectorXd& x,
             const Eigen::VectorXd& residual, AngleResult& result)
{
  if (contact)
    result.contact = contact->measure(x, t, contact_on, result.gap_mm, result.pressure_mpa);
  const FiberMeasures fibers = measure_fibers(body, x);
  result.mean_fiber_stretch = fibers.mean_fiber_stretch;
  result.max_fiber_stretch = fibers.max_fiber_stretch;
  result.min_j = fibers.min_j;
  const std::vector<Eigen::Vector3d> reactions = reaction_forces(conditions, residual);
  if (const int femur = set_index(conditions, "femur"); femur >= 0)
    result.femur_force_n = reactions[static_cast<std::size_t>(femur)];
  if (const int tibia = set_index(conditions, "tibia"); tibia >= 0)
    result.tibia_force_n = reactions[static_cast<std::size_t>(tibia)];
}

/// Equilibrium at each angle, each solve starting from the previous angle's state.
SweepResult quasi_static_sweep(const HyperelasticBody& body, const BoundaryConditions& conditions,
                               const FlexionSettings& settings, const KneeContact* contact,
                               Eigen::VectorXd& x, const AngleCallback& on_angle)
{
  SweepResult sweep;
  NewtonSettings newton = settings.newton;
  newton.load_factors = flexion_load_factors(settings.angles_deg);
  StaticSolver solver(body, conditions, newton);
  const bool contact_on = contact && settings.contact.enabled.value_or(true);
  if (contact_on)
    solver.set_extra_potential(&contact->potential());
  Progress progress("flexion angles", settings.angles_deg.size());
  const StaticResult result =
      solver.solve(x, [&](const StepReport& step, const Eigen::VectorXd& state,
                          const Eigen::VectorXd& residual) {
        AngleResult angle;
        angle.angle_deg = settings.angles_deg[static_cast<std::size_t>(step.step) - 1];
        angle.converged = step.converged;
        angle.strain_energy_mj = step.strain_energy_mj;
        angle.newton_iterations = step.iterations;
        angle.substeps = step.substeps;
        angle.relative_residual = step.relative_residual;
        angle.wall_s = step.wall_s;
        measure(body, conditions, contact, contact_on, step.load_factor, state, residual, angle);
        sweep.angles.push_back(angle);
        if (on_angle)
          on_angle(angle, state);
        progress.advance();
      });
  progress.finish();
  sweep.success = result.converged;
  if (!result.converged) {
    const std::size_t failed = result.steps.size() - 1;
    sweep.failure =
        fmt::format("flexion to {} deg: {}", settings.angles_deg[failed], result.failure);
  }
  return sweep;
}

/// Implicit Euler frames while the femur turns at the set angular speed, from the equilibrium at
/// 0 degrees; the angles of the sweep are recorded at the frames that reach them.
SweepResult interactive_sweep(const HyperelasticBody& body, const BoundaryConditions& conditions,
                              const FlexionSettings& settings, const KneeContact* contact,
                              Eigen::VectorXd& x, const AngleCallback& on_angle)
{
  const InteractiveSettings& interactive = settings.interactive;
  const std::vector<double>& angles = settings.angles_deg;
  const double last = angles.back();
  const int frames =
      std::max(1, static_cast<int>(std::ceil(
                      last / (interactive.angular_speed_deg_s * interactive.time_step_s) - 1e-9)));

  // The pre-stretched ligament settles first, with the femur at 0 degrees.
  FlexionSettings start = settings;
  start.angles_deg = {0.0};
  start.mode = FlexionMode::quasi_static;
  SweepResult sweep;
  const auto settle_start = std::chrono::steady_clock::now();
  SweepResult settled = quasi_static_sweep(body, conditions, start, contact, x, {});
  if (!settled.success) {
    settled.failure = "settling at 0 deg before the interactive sweep: " + settled.failure;
    return settled;
  }
  const AngleResult& rest = settled.angles.front();

  // The frame that reaches each angle.
  std::vector<int> angle_frames;
  for (double angle : angles)
    angle_frames.push_back(last > 0.0 ? static_cast<int>(std::lround(angle / last * frames)) : 0);
  std::size_t next = 0;
  auto record = [&](AngleResult angle, const Eigen::VectorXd& state) {
    while (next < angles.size() && angle_frames[next] == angle.frame) {
      angle.angle_deg = angles[next];
      sweep.angles.push_back(angle);
      if (on_angle)
        on_angle(angle, state);
      ++next;
    }
  };
  AngleResult first = rest;
  first.frame = 0;
  first.wall_s = seconds_since(settle_start);
  record(first, x);

  DynamicsSettings dynamics;
  dynamics.time_step_s =
      last > 0.0 ? last / (interactive.angular_speed_deg_s * frames) : interactive.time_step_s;
  dynamics.frames = frames;
  dynamics.ramp_frames = frames;
  dynamics.density_kg_m3 = interactive.density_kg_m3;
  dynamics.mass_damping_per_s = interactive.mass_damping_per_s;
  dynamics.linear_solver = interactive.linear_solver;
  dynamics.pcg = settings.newton.pcg;
  ImplicitEuler solver(body, conditions, dynamics);
  const bool contact_on = contact && settings.contact.enabled.value_or(true);
  if (contact_on)
    solver.set_extra_potential(&contact->potential());
  Progress progress("interactive frames", static_cast<std::size_t>(frames));
  auto since_recorded = std::chrono::steady_clock::now();
  int solves = 0;
  const DynamicResult result =
      solver.run(x, [&](const FrameReport& frame, const Eigen::VectorXd& state,
                        const Eigen::VectorXd& residual) {
        solves += frame.substeps;
        progress.advance();
        if (next >= angles.size() || angle_frames[next] != frame.frame)
          return;
        AngleResult angle;
        angle.frame = frame.frame;
        angle.converged = true;
        angle.strain_energy_mj = frame.strain_energy_mj;
        angle.newton_iterations = solves;
        angle.substeps = frame.substeps;
        angle.relative_residual = frame.relative_residual;
        angle.wall_s = seconds_since(since_recorded);
        measure(body, conditions, contact, contact_on, frame.load_factor, state, residual, angle);
        record(angle, state);
        solves = 0;
        since_recorded = std::chrono::steady_clock::now();
      });
  progress.finish();
  sweep.success = result.completed && next == angles.size();
  if (!result.completed)
    sweep.failure =
        fmt::format("interactive frame {} of {}: {}", result.frames + 1, frames, result.failure);
  sweep.frames = result.frames;
  sweep.time_step_s = dynamics.time_step_s;
  sweep.frames_per_second = result.frames / std::max(result.wall_s, 1e-9);
  return sweep;
}

} // namespace

std::vector<double> flexion_load_factors(const std::vector<double>& angles_deg)
{
  std::vector<double> factors;
  const double last = angles_deg.back();
  for (double angle : angles_deg)
    factors.push_back(last > 0.0 ? angle / last : 0.0);
  factors.back() = last > 0.0 ? 1.0 : 0.0; // no round-off at the end
  return factors;
}

FiberMeasures measure_fibers(const HyperelasticBody& body, const Eigen::VectorXd& x)
{
  FiberMeasures result;
  double volume = 0.0;
  double weighted_stretch = 0.0;
  for (Eigen::Index e = 0; e < body.element_count(); ++e) {
    const ElementMeasures measures = body.measures(x, e);
    const double v0 = body.shape(e).V0;
    volume += v0;
    weighted_stretch += v0 * measures.fiber_stretch;
    result.max_fiber_stretch = std::max(result.max_fiber_stretch, measures.fiber_stretch);
    result.min_j = std::min(result.min_j, measures.J);
  }
  result.mean_fiber_stretch = weighted_stretch / volume;
  return result;
}

ResolvedAxis resolve_flexion_axis(const KneeModel& model, const AxisSettings& settings)
{
  ResolvedAxis resolved;
  if (settings.source == AxisSettings::Source::points) {
    const Eigen::Vector3d direction = settings.second_mm - settings.first_mm;
    if (!direction.allFinite() || direction.norm() < 1e-9)
      fail("flexion axis: the two points {} and {} coincide: the axis has zero length",
           json_vector3(settings.first_mm).dump(), json_vector3(settings.second_mm).dump());
    resolved.axis = {settings.first_mm, direction.normalized()};
    resolved.method = "given as two points";
    resolved.figures = {{"first_mm", json_vector3(settings.first_mm)},
                        {"second_mm", json_vector3(settings.second_mm)}};
    return resolved;
  }
  if (!settings.posterior.allFinite() || settings.posterior.norm() < 1e-12)
    fail("flexion axis: fitting it to the femoral condyles needs the posterior direction of the "
         "data (--posterior x,y,z or [axis] posterior), which makes positive angles flex the "
         "knee; or give the axis as two points (--axis x1,y1,z1,x2,y2,z2)");
  const TriangleSurface femur = triangle_surface(model.femur, "femur.vtp");
  const Eigen::Vector3d proximal = proximal_direction(model);
  const CondyleAxisFit fit = fit_condyle_axis(femur, proximal, settings.posterior.normalized());
  resolved.axis = fit.axis;
  resolved.method = "cylinder fitted to the posterior femoral condyles";
  resolved.figures = {{"radius_mm", fit.radius_mm},
                      {"rms_residual_mm", fit.rms_residual_mm},
                      {"points_used", fit.points_used},
                      {"points_considered", fit.points_considered},
                      {"proximal", json_vector3(proximal)},
                      {"posterior_hint", json_vector3(settings.posterior.normalized())}};
  return resolved;
}

FiberField prestretched_fibers(const KneeModel& model, double in_situ_strain)
{
  return model.fiber_directions * (1.0 + in_situ_strain);
}

BoundaryConditions knee_conditions(const KneeModel& model, const FlexionAxis& axis,
                                   double last_angle_deg)
{
  BoundaryConditions conditions;
  ConstraintSet tibia;
  tibia.name = "tibia";
  tibia.nodes = model.tibia_nodes;
  conditions.constraints.push_back(tibia);

  ConstraintSet femur;
  femur.name = "femur";
  femur.nodes = model.femur_nodes;
  RigidMotion motion;
  motion.axis = axis.direction.normalized();
  motion.point_mm = axis.point_mm;
  motion.angle_rad = last_angle_deg * degree;
  femur.rigid = motion;
  conditions.constraints.push_back(femur);
  return conditions;
}

SweepResult run_flexion_sweep(const HyperelasticBody& body, const BoundaryConditions& conditions,
                              const FlexionSettings& settings, const AngleCallback& on_angle,
                              const KneeContact* contact)
{
  validate(settings);
  const auto start = std::chrono::steady_clock::now();
  Eigen::VectorXd x = body.rest_positions();
  const double unrelaxed = body.energy(x).energy;
  SweepResult sweep = settings.mode == FlexionMode::quasi_static
                          ? quasi_static_sweep(body, conditions, settings, contact, x, on_angle)
                          : interactive_sweep(body, conditions, settings, contact, x, on_angle);
  sweep.unrelaxed_energy_mj = unrelaxed;
  sweep.wall_s = seconds_since(start);
  return sweep;
}

} // namespace ligsim::sim
