#include "sim/kinematics/knee_path.hpp"

#include "common/error.hpp"

#include <algorithm>
#include <cmath>

namespace ligsim::sim {

namespace {

constexpr double passive_limit_deg = 120.0;

JointPose blend(const JointPose& a, const JointPose& b, double w)
{
  auto mix = [w](double p, double q) { return (1.0 - w) * p + w * q; };
  return {mix(a.flexion_deg, b.flexion_deg),
          mix(a.varus_deg, b.varus_deg),
          mix(a.internal_rotation_deg, b.internal_rotation_deg),
          mix(a.lateral_mm, b.lateral_mm),
          mix(a.anterior_mm, b.anterior_mm),
          mix(a.proximal_mm, b.proximal_mm)};
}

} // namespace

JointPose passive_coupling(double flexion_deg, bool translations)
{
  // Walker et al. 1988 give the femur relative to the tibia; these are the tibia's coordinates
  // relative to the femur: rotations as printed (adduction and internal rotation positive),
  // translations negated.
  const double d = std::clamp(flexion_deg, 0.0, passive_limit_deg);
  JointPose pose;
  pose.flexion_deg = flexion_deg;
  pose.varus_deg = 0.0791 * d - 5.733e-4 * d * d - 7.682e-6 * d * d * d + 5.759e-8 * d * d * d * d;
  pose.internal_rotation_deg = 0.3695 * d - 2.958e-3 * d * d + 7.666e-6 * d * d * d;
  if (translations) {
    pose.proximal_mm = -(-0.0683 * d + 8.804e-4 * d * d - 3.75e-6 * d * d * d);
    pose.anterior_mm = -(-0.1283 * d + 4.796e-4 * d * d);
  }
  return pose;
}

KneePath KneePath::pure_flexion()
{
  KneePath path;
  path.m_kind = Kind::pure;
  path.m_description = "pure flexion about the flexion axis";
  return path;
}

KneePath KneePath::passive(bool translations)
{
  KneePath path;
  path.m_kind = Kind::passive;
  path.m_translations = translations;
  path.m_description = std::string("passive flexion: varus and internal tibial rotation") +
                       (translations ? " and tibial translations" : "") +
                       " coupled to flexion (Walker et al., J Biomech 1988;21:965)";
  return path;
}

KneePath KneePath::table(Parameter parameter, std::vector<double> knots,
                         std::vector<JointPose> poses, std::string source)
{
  if (knots.empty() || knots.size() != poses.size())
    fail("knee path {}: {} rows of coordinates for {} values of the parameter", source,
         poses.size(), knots.size());
  for (std::size_t k = 1; k < knots.size(); ++k)
    if (!(knots[k] > knots[k - 1]))
      fail("knee path {}: the {} must increase from row to row ({} after {})", source,
           parameter == Parameter::time_s ? "time" : "flexion angle", knots[k], knots[k - 1]);
  KneePath path;
  path.m_kind = Kind::table;
  path.m_parameter = parameter;
  path.m_knots = std::move(knots);
  path.m_poses = std::move(poses);
  path.m_description = fmt::format("{} rows by {} from {}", path.m_knots.size(),
                                   parameter == Parameter::time_s ? "time" : "flexion", source);
  return path;
}

JointPose KneePath::at(double value) const
{
  switch (m_kind) {
  case Kind::pure: {
    JointPose pose;
    pose.flexion_deg = value;
    return pose;
  }
  case Kind::passive:
    return passive_coupling(value, m_translations);
  case Kind::table:
    break;
  }
  if (value <= m_knots.front())
    return m_poses.front();
  if (value >= m_knots.back())
    return m_poses.back();
  const auto upper = std::upper_bound(m_knots.begin(), m_knots.end(), value);
  const auto k = static_cast<std::size_t>(upper - m_knots.begin());
  const double w = (value - m_knots[k - 1]) / (m_knots[k] - m_knots[k - 1]);
  return blend(m_poses[k - 1], m_poses[k], w);
}

FemurPath::FemurPath(JointCoordinateSystem jcs, KneePath path, double first, double last)
    : m_jcs(std::move(jcs))
    , m_path(std::move(path))
    , m_first(first)
    , m_last(last)
{
  joint_axes(m_jcs); // validates the axes once, with a clear error
}

JointPose FemurPath::joint_pose_at(double t) const
{
  return m_path.at(m_first + t * (m_last - m_first));
}

Eigen::Isometry3d FemurPath::pose(double t) const
{
  return femur_motion(m_jcs, joint_pose_at(t));
}

} // namespace ligsim::sim
