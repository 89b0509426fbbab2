#pragma once
/// @brief The knee's motion as Grood & Suntay coordinates along a parameter (the flexion angle,
/// or the time of a recorded motion): pure flexion, flexion with the passive knee's coupled
/// motions, or a table read from a CSV file as robot and motion-capture labs export them.

#include "sim/kinematics/joint_coordinates.hpp"
#include "sim/solver/boundary_conditions.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace ligsim::sim {

class KneePath {
public:
  enum class Parameter { flexion_deg, time_s };

  /// Flexion alone: every other coordinate stays 0.
  static KneePath pure_flexion();
  /// Flexion with the tibial rotations of the unloaded passive knee coupled to it (see
  /// passive_coupling), and its translations when `translations` is true.
  static KneePath passive(bool translations);
  /// Rows of a table, sorted by their parameter (strictly increasing), linearly interpolated.
  static KneePath table(Parameter parameter, std::vector<double> knots,
                        std::vector<JointPose> poses, std::string source);

  Parameter parameter() const { return m_parameter; }
  /// The coordinates at `value` of the parameter. A table is held at its ends outside them.
  JointPose at(double value) const;
  /// The table's knots (empty for pure and passive paths).
  const std::vector<double>& knots() const { return m_knots; }
  const std::vector<JointPose>& poses() const { return m_poses; }
  /// What the path is, for summary.json and stderr.
  const std::string& description() const { return m_description; }

private:
  enum class Kind { pure, passive, table };
  Kind m_kind = Kind::pure;
  Parameter m_parameter = Parameter::flexion_deg;
  bool m_translations = false;
  std::vector<double> m_knots;
  std::vector<JointPose> m_poses;
  std::string m_description;
};

/// The passive knee's coupled motion at a flexion angle (deg): Walker, Rovick & Robertson,
/// J Biomech 1988;21:965, as used by OpenSim's knee of Rajagopal et al. (IEEE Trans Biomed
/// Eng 2016;63:2068). Varus and internal tibial rotation, deg, and with `translations` the
/// tibia's anterior and proximal shift, mm. Their polynomials hold from 0 to 120 degrees; past
/// 120 the coupling stays at its 120-degree value. Internal rotation 4.9, 8.6, 13.2, 14.9 and
/// 15.0 degrees at 15, 30, 60, 90 and 120 degrees of flexion.
JointPose passive_coupling(double flexion_deg, bool translations);

/// The femur's motion for a solver: the knee path in the joint coordinate system, its parameter
/// running linearly from `first` at load factor 0 to `last` at load factor 1.
class FemurPath final : public RigidPath {
public:
  FemurPath(JointCoordinateSystem jcs, KneePath path, double first, double last);
  Eigen::Isometry3d pose(double t) const override;
  /// The knee's coordinates at load factor t.
  JointPose joint_pose_at(double t) const;
  const JointCoordinateSystem& jcs() const { return m_jcs; }
  const KneePath& path() const { return m_path; }

private:
  JointCoordinateSystem m_jcs;
  KneePath m_path;
  double m_first = 0.0;
  double m_last = 0.0;
};

} // namespace ligsim::sim
