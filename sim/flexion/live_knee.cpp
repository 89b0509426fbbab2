#include "sim/flexion/live_knee.hpp"

#include "common/error.hpp"
#include "sim/flexion/knee_flexion.hpp"
#include "sim/flexion/knee_sweep.hpp"
#include "sim/solver/parallel.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace ligsim::sim {

LiveKnee::LiveKnee(const std::vector<LigamentModel>& ligaments, const KneeMotion& motion,
                   const FlexionSettings& settings, const std::filesystem::path& contact_cache,
                   double max_angle_deg)
    : m_motion(motion)
    , m_time_step_s(settings.interactive.time_step_s)
    , m_speed_deg_s(settings.interactive.angular_speed_deg_s)
    , m_max_angle_deg(max_angle_deg)
    , m_contact(settings.contact.enabled.value_or(true))
{
  if (!motion.femur_path ||
      motion.femur_path->path().parameter() != KneePath::Parameter::flexion_deg)
    fail("view: the knee's path is a motion in time; the view moves the flexion angle (give a "
         "path by flexion angle)");
  if (!(max_angle_deg > 0.0))
    fail("view: the largest angle must be positive, not {}", max_angle_deg);
  m_ligaments.reserve(ligaments.size());
  for (const LigamentModel& ligament : ligaments) {
    FlexionSettings own = ligament_settings(settings, ligament);
    own.mode = FlexionMode::quasi_static;
    m_ligaments.emplace_back(ligament, own, motion.jcs, contact_cache);
  }
  std::vector<char> settled(m_ligaments.size());
  const JointPose start = pose_at(0.0);
  parallel_tasks(m_ligaments.size(), [&](std::size_t l) {
    settled[l] = m_ligaments[l].settle() && m_ligaments[l].move_to(start) ? 1 : 0;
  });
  for (std::size_t l = 0; l < m_ligaments.size(); ++l) {
    if (!settled[l])
      fail<SolverError>("view: settling at 0 deg: {}", m_ligaments[l].failure());
    m_regions.push_back(
        element_regions(m_ligaments[l].body(), settings.ligament.strain_region_radius_mm));
  }
  measure();
}

JointPose LiveKnee::pose_at(double angle_deg) const
{
  JointPose pose = m_motion.femur_path->path().at(angle_deg);
  pose.flexion_deg = angle_deg;
  return pose;
}

Eigen::Isometry3d LiveKnee::femur_pose() const
{
  return femur_motion(m_motion.jcs, pose_at(m_angle_deg));
}

const LiveFrame& LiveKnee::advance(double target_deg)
{
  const auto start = std::chrono::steady_clock::now();
  target_deg = std::clamp(target_deg, 0.0, m_max_angle_deg);
  const double reach = m_speed_deg_s * m_time_step_s;
  const double angle = m_angle_deg + std::clamp(target_deg - m_angle_deg, -reach, reach);
  const JointPose pose = pose_at(angle);
  std::vector<FrameReport> reports(m_ligaments.size());
  std::vector<char> done(m_ligaments.size());
  parallel_tasks(m_ligaments.size(), [&](std::size_t l) {
    done[l] = m_ligaments[l].frame_to(pose, m_time_step_s, reports[l]) ? 1 : 0;
  });
  for (std::size_t l = 0; l < m_ligaments.size(); ++l)
    if (!done[l])
      fail<SolverError>("view at {:.1f} deg: {}", angle, m_ligaments[l].failure());
  m_angle_deg = angle;
  ++m_last.frame;
  m_last.time_s = m_last.frame * m_time_step_s;
  m_last.target_deg = target_deg;
  m_last.solves = 0;
  m_last.equation_met = true;
  for (const FrameReport& report : reports) {
    m_last.solves += report.factorizations + report.linear_iterations;
    m_last.equation_met = m_last.equation_met && report.equation_met;
  }
  measure();
  m_last.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return m_last;
}

void LiveKnee::measure()
{
  m_last.angle_deg = m_angle_deg;
  m_last.ligaments.resize(m_ligaments.size());
  m_strain.resize(m_ligaments.size());
  parallel_tasks(m_ligaments.size(), [&](std::size_t l) {
    const LigamentAtPose& ligament = m_ligaments[l];
    const HyperelasticBody& body = ligament.body();
    Eigen::VectorXd& strain = m_strain[l];
    strain.resize(body.element_count());
    for (Eigen::Index e = 0; e < body.element_count(); ++e)
      strain[e] = body.measures(ligament.positions(), e).fiber_stretch - 1.0;
    m_last.ligaments[l] = {ligament.name(), ligament.footprint_force().norm(),
                           100.0 * m_regions[l].max_mean(strain)};
  });
}

void LiveKnee::set_contact(bool on)
{
  m_contact = on;
  for (LigamentAtPose& ligament : m_ligaments)
    ligament.set_contact(on);
}

} // namespace ligsim::sim
