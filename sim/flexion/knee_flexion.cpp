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
#include <optional>

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

/// What the measures of each angle need besides the state.
struct Measuring {
  const HyperelasticBody& body;
  const BoundaryConditions& conditions;
  const KneeContact* contact;
  bool contact_on;
  double failure_strain;
  const RegionalMean& regions;
  const EmbeddedPolyline* centerline;
  double reference_length_mm; ///< NaN until the first angle at 0 degrees (or the rest shape's)
};

/// Energy, fiber stretch, attachment forces, length and contact of state `x` at load factor t.
void measure(Measuring& m, double t, const Eigen::VectorXd& x, const Eigen::VectorXd& residual,
             AngleResult& result)
{
  const HyperelasticBody& body = m.body;
  if (m.contact)
    result.contact = m.contact->measure(x, t, m.contact_on, result.gap_mm, result.pressure_mpa);
  const FiberMeasures fibers = measure_fibers(body, x, m.failure_strain, &m.regions);
  result.mean_fiber_stretch = fibers.mean_fiber_stretch;
  result.max_fiber_stretch = fibers.max_fiber_stretch;
  result.max_regional_fiber_stretch = fibers.max_regional_fiber_stretch;
  result.min_j = fibers.min_j;
  result.failed_volume_fraction = fibers.failed_volume_fraction;
  if (m.centerline) {
    result.length_mm = m.centerline->length(x);
    if (std::isnan(m.reference_length_mm))
      m.reference_length_mm =
          result.angle_deg == 0.0 ? result.length_mm : m.centerline->length(body.rest_positions());
    result.length_change_mm = result.length_mm - m.reference_length_mm;
    result.length_change_pct = 100.0 * result.length_change_mm / m.reference_length_mm;
  }
  const std::vector<Eigen::Vector3d> reactions = reaction_forces(m.conditions, residual);
  if (const int femur = set_index(m.conditions, "femur"); femur >= 0)
    result.femur_force_n = reactions[static_cast<std::size_t>(femur)];
  if (const int tibia = set_index(m.conditions, "tibia"); tibia >= 0)
    result.tibia_force_n = reactions[static_cast<std::size_t>(tibia)];
}

/// Equilibrium at each angle, each solve starting from the previous angle's state.
SweepResult quasi_static_sweep(Measuring& measuring, const FlexionSettings& settings,
                               const SweepSteps& steps, Eigen::VectorXd& x,
                               const AngleCallback& on_angle)
{
  const HyperelasticBody& body = measuring.body;
  const BoundaryConditions& conditions = measuring.conditions;
  const KneeContact* contact = measuring.contact;
  SweepResult sweep;
  NewtonSettings newton = settings.newton;
  newton.load_factors = steps.load_factors;
  StaticSolver solver(body, conditions, newton);
  const bool contact_on = contact && settings.contact.enabled.value_or(true);
  if (contact_on)
    solver.set_extra_potential(&contact->potential());
  solver.set_step_starts(steps.starts);
  Progress progress("flexion angles", steps.angles_deg.size());
  const StaticResult result =
      solver.solve(x, [&](const StepReport& step, const Eigen::VectorXd& state,
                          const Eigen::VectorXd& residual) {
        AngleResult angle;
        const auto k = static_cast<std::size_t>(step.step) - 1;
        angle.angle_deg = steps.angles_deg[k];
        angle.load_factor = step.load_factor;
        if (!steps.times_s.empty())
          angle.time_s = steps.times_s[k];
        angle.converged = step.converged;
        angle.strain_energy_mj = step.strain_energy_mj;
        angle.newton_iterations = step.iterations;
        angle.substeps = step.substeps;
        angle.shifted_iterations = step.shifted_iterations;
        angle.relative_residual = step.relative_residual;
        angle.wall_s = step.wall_s;
        measure(measuring, step.load_factor, state, residual, angle);
        sweep.angles.push_back(angle);
        if (on_angle)
          on_angle(angle, body, state);
        progress.advance();
      });
  progress.finish();
  sweep.success = result.converged;
  if (!result.converged) {
    const std::size_t failed = result.steps.size() - 1;
    sweep.failure =
        steps.times_s.empty()
            ? fmt::format("flexion to {} deg: {}", steps.angles_deg[failed], result.failure)
            : fmt::format("the knee's motion at {} s ({} deg): {}", steps.times_s[failed],
                          steps.angles_deg[failed], result.failure);
  }
  return sweep;
}

/// Implicit Euler frames while the femur turns at the set angular speed, from the equilibrium at
/// 0 degrees; the angles of the sweep are recorded at the frames that reach them.
SweepResult interactive_sweep(Measuring& measuring, const FlexionSettings& settings,
                              const SweepSteps& steps, Eigen::VectorXd& x,
                              const AngleCallback& on_angle)
{
  const HyperelasticBody& body = measuring.body;
  const BoundaryConditions& conditions = measuring.conditions;
  const KneeContact* contact = measuring.contact;
  const InteractiveSettings& interactive = settings.interactive;
  const std::vector<double>& angles = steps.angles_deg;
  const double last = angles.back();
  const int frames =
      std::max(1, static_cast<int>(std::ceil(
                      last / (interactive.angular_speed_deg_s * interactive.time_step_s) - 1e-9)));

  // The pre-stretched ligament settles first, with the femur at 0 degrees.
  FlexionSettings start = settings;
  start.mode = FlexionMode::quasi_static;
  SweepResult sweep;
  const auto settle_start = std::chrono::steady_clock::now();
  SweepResult settled = quasi_static_sweep(measuring, start, angle_steps({0.0}), x, {});
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
        on_angle(angle, body, state);
      ++next;
    }
  };
  AngleResult first = rest;
  first.frame = 0;
  first.wall_s = seconds_since(settle_start);
  record(first, x);

  DynamicsSettings dynamics =
      interactive_dynamics(settings, last > 0.0 ? last / (interactive.angular_speed_deg_s * frames)
                                                : interactive.time_step_s);
  dynamics.frames = frames;
  dynamics.ramp_frames = frames;
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
        angle.load_factor = frame.load_factor;
        // A frame whose solves ran out before its equation held is not the pose's state.
        angle.converged = frame.equation_met;
        angle.strain_energy_mj = frame.strain_energy_mj;
        angle.newton_iterations = solves;
        angle.substeps = frame.substeps;
        angle.relative_residual = frame.relative_residual;
        angle.wall_s = seconds_since(since_recorded);
        measure(measuring, frame.load_factor, state, residual, angle);
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

DynamicsSettings interactive_dynamics(const FlexionSettings& settings, double time_step_s)
{
  const InteractiveSettings& interactive = settings.interactive;
  DynamicsSettings dynamics;
  dynamics.time_step_s = time_step_s;
  dynamics.density_kg_m3 = interactive.density_kg_m3;
  dynamics.mass_damping_per_s = interactive.mass_damping_per_s;
  dynamics.linear_solver = interactive.linear_solver;
  dynamics.max_iterations = interactive.max_iterations;
  dynamics.iteration_tolerance = interactive.iteration_tolerance;
  dynamics.pcg = settings.newton.pcg;
  return dynamics;
}

FiberMeasures measure_fibers(const HyperelasticBody& body, const Eigen::VectorXd& x,
                             double failure_strain, const RegionalMean* regions)
{
  FiberMeasures result;
  double volume = 0.0;
  double weighted_stretch = 0.0;
  double failed_volume = 0.0;
  Eigen::VectorXd stretches(body.element_count());
  for (Eigen::Index e = 0; e < body.element_count(); ++e) {
    const ElementMeasures measures = body.measures(x, e);
    stretches[e] = measures.fiber_stretch;
    const double v0 = body.element_volume(e);
    volume += v0;
    weighted_stretch += v0 * measures.fiber_stretch;
    if (measures.fiber_stretch - 1.0 > failure_strain)
      failed_volume += v0;
    result.max_fiber_stretch = std::max(result.max_fiber_stretch, measures.fiber_stretch);
    result.min_j = std::min(result.min_j, measures.J);
  }
  result.mean_fiber_stretch = weighted_stretch / volume;
  result.failed_volume_fraction = failed_volume / volume;
  if (regions)
    result.max_regional_fiber_stretch = regions->max_mean(stretches);
  return result;
}

RegionalMean element_regions(const HyperelasticBody& body, double radius_mm)
{
  const TetMesh& mesh = body.mesh();
  Eigen::MatrixX3d centroids(mesh.T.rows(), 3);
  Eigen::VectorXd volumes(mesh.T.rows());
  for (Eigen::Index e = 0; e < mesh.T.rows(); ++e) {
    centroids.row(e) = 0.25 * (mesh.V.row(mesh.T(e, 0)) + mesh.V.row(mesh.T(e, 1)) +
                               mesh.V.row(mesh.T(e, 2)) + mesh.V.row(mesh.T(e, 3)));
    volumes[e] = body.element_volume(e);
  }
  return RegionalMean(centroids, volumes, radius_mm);
}

SweepSteps angle_steps(const std::vector<double>& angles_deg)
{
  SweepSteps steps;
  steps.angles_deg = angles_deg;
  const double last = angles_deg.empty() ? 0.0 : angles_deg.back();
  for (double angle : angles_deg)
    steps.load_factors.push_back(last > 0.0 ? angle / last : 0.0);
  if (!steps.load_factors.empty())
    steps.load_factors.back() = last > 0.0 ? 1.0 : 0.0; // no round-off at the end
  return steps;
}

SweepSteps motion_steps(const KneeMotion& motion)
{
  return {motion.angles_deg, motion.load_factors, motion.times_s, {}};
}

BoundaryConditions knee_conditions(const KneeModel& model, const FlexionAxis& axis,
                                   double last_angle_deg)
{
  RigidMotion motion;
  motion.axis = axis.direction.normalized();
  motion.point_mm = axis.point_mm;
  motion.angle_rad = last_angle_deg * degree;
  return knee_conditions(model, motion);
}

BoundaryConditions knee_conditions(const KneeModel& model, const RigidMotion& femur_motion)
{
  BoundaryConditions conditions;
  ConstraintSet tibia;
  tibia.name = "tibia";
  tibia.nodes = model.tibia_nodes;
  conditions.constraints.push_back(tibia);

  ConstraintSet femur;
  femur.name = "femur";
  femur.nodes = model.femur_nodes;
  femur.rigid = femur_motion;
  conditions.constraints.push_back(femur);
  return conditions;
}

SweepResult run_flexion_sweep(const HyperelasticBody& body, const BoundaryConditions& conditions,
                              const FlexionSettings& settings, const AngleCallback& on_angle,
                              const KneeContact* contact, const SweepSteps* given_steps,
                              const EmbeddedPolyline* centerline)
{
  validate(settings);
  const SweepSteps steps = given_steps ? *given_steps : angle_steps(settings.angles_deg);
  if (steps.angles_deg.empty() || steps.angles_deg.size() != steps.load_factors.size())
    fail("flexion: {} angles for {} load factors", steps.angles_deg.size(),
         steps.load_factors.size());
  const auto start = std::chrono::steady_clock::now();
  Eigen::VectorXd x = body.rest_positions();
  const double unrelaxed = body.energy(x).energy;
  OverlapReport overlap;
  std::optional<HyperelasticBody> reshaped;
  if (contact && settings.contact.enabled.value_or(true)) {
    try {
      if (settings.contact.reshape_overlap) {
        overlap = reshape_initial_overlap(body, settings.material, conditions, *contact,
                                          settings.newton, x);
        if (overlap.reshaped)
          reshaped.emplace(with_rest_shape(body, settings.material, x));
      } else {
        overlap = resolve_initial_overlap(body, conditions, *contact, settings.newton, x);
      }
    } catch (const SolverError& e) {
      SweepResult failed;
      failed.failure = e.what();
      failed.unrelaxed_energy_mj = unrelaxed;
      return failed;
    }
  } else if (contact) {
    overlap.before = contact->gaps(x, 0.0);
  }
  const HyperelasticBody& swept = reshaped ? *reshaped : body;
  const RegionalMean regions = element_regions(swept, settings.ligament.strain_region_radius_mm);
  Measuring measuring{swept,
                      conditions,
                      contact,
                      contact && settings.contact.enabled.value_or(true),
                      settings.ligament.failure_strain,
                      regions,
                      centerline,
                      NAN};
  SweepResult sweep = settings.mode == FlexionMode::quasi_static
                          ? quasi_static_sweep(measuring, settings, steps, x, on_angle)
                          : interactive_sweep(measuring, settings, steps, x, on_angle);
  sweep.unrelaxed_energy_mj = unrelaxed;
  sweep.overlap = std::move(overlap);
  sweep.wall_s = seconds_since(start);
  return sweep;
}

Eigen::Vector3d net_force(const AngleResult& angle, const std::string& bone,
                          const Eigen::Vector3d& footprint_n)
{
  Eigen::Vector3d net = footprint_n;
  for (const BoneContact& contact : angle.contact)
    if (contact.bone == bone && contact.in_solve)
      net += contact.force_n;
  return net;
}

Eigen::Vector3d femur_net_force(const AngleResult& angle)
{
  return net_force(angle, "femur", angle.femur_force_n);
}

} // namespace ligsim::sim
