#include "sim/flexion/ligament_at_pose.hpp"

#include "common/error.hpp"
#include "sim/flexion/knee_flexion.hpp"
#include "sim/solver/condensed_stiffness.hpp"

#include <array>
#include <cmath>

namespace ligsim::sim {

namespace {

constexpr std::size_t kFemurSet = 1; // knee_conditions: "tibia", then "femur"

} // namespace

LigamentAtPose::LigamentAtPose(const LigamentModel& ligament, const FlexionSettings& settings,
                               const JointCoordinateSystem& jcs,
                               const std::filesystem::path& contact_cache)
    : m_name(ligament.name)
    , m_ligament(ligament)
    , m_settings(settings)
    , m_jcs(jcs)
    , m_segment(std::make_shared<PoseSegment>(jcs))
{
  const KneeModel& model = ligament.model;
  RigidMotion motion;
  motion.path = m_segment;
  m_conditions = knee_conditions(model, motion);
  m_contact = std::make_unique<KneeContact>(model, m_conditions, settings.contact, contact_cache);
  m_contact_on = settings.contact.enabled.value_or(true);
  const auto& obstacles = m_contact->potential().obstacles();
  for (std::size_t o = 0; o < obstacles.size(); ++o)
    if (obstacles[o].name == "femur")
      m_femur_obstacle = static_cast<int>(o);
  m_body.emplace(ligament_body(model, settings.material, settings.in_situ_strain));
  m_x = m_body->rest_positions();
}

void LigamentAtPose::make_solver()
{
  NewtonSettings newton = m_settings.newton;
  newton.load_factors = {1.0};
  m_solver = std::make_unique<StaticSolver>(*m_body, m_conditions, newton);
  if (m_contact_on)
    m_solver->set_extra_potential(&m_contact->potential());
}

bool LigamentAtPose::settle()
{
  if (m_contact_on) {
    try {
      if (m_settings.contact.reshape_overlap) {
        const OverlapReport overlap = reshape_initial_overlap(
            *m_body, m_settings.material, m_conditions, *m_contact, m_settings.newton, m_x);
        if (overlap.reshaped) {
          HyperelasticBody reshaped = with_rest_shape(*m_body, m_settings.material, m_x);
          m_body.emplace(std::move(reshaped));
        }
      } else {
        resolve_initial_overlap(*m_body, m_conditions, *m_contact, m_settings.newton, m_x);
      }
    } catch (const SolverError& e) {
      m_failure = fmt::format("{}: pushing it out of the bones: {}", m_name, e.what());
      return false;
    }
  }
  make_solver();
  return move_to(m_pose);
}

bool LigamentAtPose::move_to(const JointPose& pose)
{
  m_segment->set(m_pose, pose);
  const Eigen::VectorXd saved = m_x;
  Eigen::VectorXd residual;
  const auto solve = [&] {
    return m_solver->solve(m_x, [&](const StepReport&, const Eigen::VectorXd&,
                                    const Eigen::VectorXd& r) { residual = r; });
  };
  // Near the pose the response was computed at: start from the equilibrium it predicts (the
  // solve then needs fewer steps), and from the last one if that start is no state (an element
  // inverted) or cannot be solved (a predicted node inside a bone).
  const std::optional<Eigen::VectorXd> guess = predicted_positions(pose);
  const bool predicted = guess && std::isfinite(m_body->energy(*guess).energy);
  if (predicted)
    m_x = *guess;
  StaticResult result = solve();
  if (!result.converged && predicted) {
    m_x = saved;
    result = solve();
  }
  if (!result.converged) {
    m_x = saved;
    m_segment->set(m_pose, m_pose);
    m_failure = fmt::format("{}: {}", m_name, result.failure);
    return false;
  }
  m_pose = pose;
  m_segment->set(pose, pose);
  m_residual = residual;
  return true;
}

std::optional<Eigen::VectorXd> LigamentAtPose::predicted_positions(const JointPose& pose) const
{
  if (!m_response_pose || m_response_pose->flexion_deg != m_pose.flexion_deg ||
      free_coordinates(*m_response_pose) != free_coordinates(m_pose) ||
      pose.flexion_deg != m_pose.flexion_deg)
    return std::nullopt;
  Eigen::VectorXd x = m_x + m_response * (free_coordinates(pose) - free_coordinates(m_pose));
  // The response moves the free nodes only; the femoral footprint goes with the femur (left
  // behind, it shears the elements between them by the whole move, and a few degrees invert
  // them).
  // (As the solver's path puts it at its end, to the bit: a round-off shift left would cost the
  // solve a predictor.)
  PoseSegment path(m_jcs);
  path.set(m_pose, pose);
  const Eigen::Isometry3d femur = path.pose(1.0);
  const Points& rest = m_body->mesh().V;
  for (int n : m_conditions.constraints[kFemurSet].nodes)
    x.segment<3>(3 * n) = femur * Eigen::Vector3d(rest.row(n).transpose());
  return x;
}

void LigamentAtPose::restore(const Equilibrium& equilibrium)
{
  m_pose = equilibrium.pose;
  m_x = equilibrium.positions;
  m_residual = equilibrium.residual;
  m_segment->set(m_pose, m_pose);
}

double LigamentAtPose::energy() const
{
  double e = m_body->energy(m_x).energy;
  if (m_contact_on)
    e += m_contact->potential().energy(m_x, 1.0, nullptr);
  return e;
}

Vector5d LigamentAtPose::generalized_force(const FreePose& pose) const
{
  Vector5d g = Vector5d::Zero();
  const Points& rest = m_body->mesh().V;
  for (int n : m_conditions.constraints[kFemurSet].nodes)
    g += pose.jacobian(rest.row(n).transpose()).transpose() * m_residual.segment<3>(3 * n);
  if (m_contact_on && m_femur_obstacle >= 0)
    for (const ContactPotential::NodeTerm& term :
         m_contact->potential().node_terms(static_cast<std::size_t>(m_femur_obstacle), m_x, 1.0))
      g -= pose.jacobian(term.local_mm).transpose() * term.gradient;
  return g;
}

Matrix5d LigamentAtPose::stiffness(const FreePose& pose) const
{
  const Points& rest = m_body->mesh().V;
  const int dofs = m_body->dof_count();
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(dofs, 5), coupling = Eigen::MatrixXd::Zero(dofs, 5);
  Matrix5d curvature = Matrix5d::Zero();
  for (int n : m_conditions.constraints[kFemurSet].nodes) {
    const Eigen::Vector3d X = rest.row(n).transpose();
    D.block<3, 5>(3 * n, 0) = pose.jacobian(X);
    curvature += pose.weighted_second(X, m_residual.segment<3>(3 * n));
  }
  if (m_contact_on && m_femur_obstacle >= 0) {
    // The barrier of node i is e(y), y = L^T (x - s) the node in the femur's frame. With
    // J = d(L y + s)/dq at y and B_k = dL/dq_k L^T (skew: L is a rotation):
    // d^2E/dx dq_k = -H J_k + B_k g, and
    // d^2E/dq_k dq_l = J_k^T H J_l - g . d^2(L y + s)/dq_k dq_l - J_k . B_l g - J_l . B_k g.
    std::array<Eigen::Matrix3d, 5> B;
    for (int k = 0; k < 5; ++k)
      B[static_cast<std::size_t>(k)] = pose.rotation_derivative(k) * pose.rotation().transpose();
    for (const ContactPotential::NodeTerm& term :
         m_contact->potential().node_terms(static_cast<std::size_t>(m_femur_obstacle), m_x, 1.0)) {
      const Matrix35d J = pose.jacobian(term.local_mm);
      Matrix35d Bg;
      for (int k = 0; k < 5; ++k)
        Bg.col(k) = B[static_cast<std::size_t>(k)] * term.gradient;
      coupling.block<3, 5>(3 * term.node, 0) += Bg - term.hessian * J;
      const Matrix5d cross = J.transpose() * Bg; // (k, l): J_k . B_l g
      curvature += J.transpose() * term.hessian * J -
                   pose.weighted_second(term.local_mm, term.gradient) - cross - cross.transpose();
    }
  }
  const CondensedStiffness S =
      condensed_stiffness(*m_body, m_conditions, m_x,
                          m_contact_on ? &m_contact->potential() : nullptr, 1.0, D, &coupling);
  m_response = S.free_response;
  m_response_pose = m_pose;
  Matrix5d K = S.matrix + curvature;
  return 0.5 * (K + K.transpose());
}

bool LigamentAtPose::frame_to(const JointPose& pose, double time_step_s, FrameReport& report)
{
  if (!m_dynamics) {
    m_dynamics = std::make_unique<ImplicitEuler>(*m_body, m_conditions,
                                                 interactive_dynamics(m_settings, time_step_s));
    if (m_contact_on)
      m_dynamics->set_extra_potential(&m_contact->potential());
    m_dynamics->start(m_x);
    m_velocity = Eigen::VectorXd::Zero(m_x.size());
  }
  m_segment->set(m_pose, pose);
  report.load_factor = 1.0;
  Eigen::VectorXd residual;
  if (!m_dynamics->frame(m_x, m_velocity, 0.0, report, residual)) {
    m_segment->set(m_pose, m_pose);
    m_failure = fmt::format("{}: frame {}", m_name, m_dynamics->failure());
    return false;
  }
  m_pose = pose;
  m_segment->set(pose, pose);
  m_residual = residual;
  return true;
}

void LigamentAtPose::set_contact(bool on)
{
  m_contact_on = on;
  const ExtraPotential* potential = on ? &m_contact->potential() : nullptr;
  if (m_solver)
    m_solver->set_extra_potential(potential);
  if (m_dynamics)
    m_dynamics->set_extra_potential(potential);
}

Eigen::Vector3d LigamentAtPose::footprint_force() const
{
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  for (int n : m_conditions.constraints[kFemurSet].nodes)
    force += m_residual.segment<3>(3 * n);
  return force;
}

Eigen::Vector3d LigamentAtPose::femur_force() const
{
  Eigen::Vector3d force = footprint_force();
  if (m_contact_on && m_femur_obstacle >= 0)
    for (const ContactPotential::NodeTerm& term :
         m_contact->potential().node_terms(static_cast<std::size_t>(m_femur_obstacle), m_x, 1.0))
      force -= term.gradient; // the barrier's force on the node: -dE/dx
  return force;
}

} // namespace ligsim::sim
