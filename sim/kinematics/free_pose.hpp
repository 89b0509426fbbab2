#pragma once
/// @brief The femur's pose at a held flexion angle as a function of the knee's five other
/// Grood & Suntay coordinates, with exact first and second derivatives of where a femur-fixed
/// point goes: what a solver needs to make those coordinates unknowns.
///
/// With the tibia fixed, the femur moves by x = R^T (X - O) + O - v (joint_coordinates.cpp),
/// R = A(flexion) B(varus) C(internal) the Cardan rotations about the JCS's rest axes, v the
/// tibia's translation in them. The free coordinates q, in this order: varus and internal
/// rotation (rad), lateral, anterior and proximal translation of the tibia (mm). A rotation is
/// scaled by `rotation_scale_mm` in the solver's unknowns (q_k * scale mm), so that a unit step
/// moves points near the joint by about a millimetre either way.

#include "sim/kinematics/joint_coordinates.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>

namespace ligsim::sim {

using Vector5d = Eigen::Matrix<double, 5, 1>;
using Matrix5d = Eigen::Matrix<double, 5, 5>;
using Matrix35d = Eigen::Matrix<double, 3, 5>;

/// The free coordinates of a joint pose (its flexion aside), in the order above.
Vector5d free_coordinates(const JointPose& pose);
/// The joint pose of flexion `flexion_deg` and free coordinates q.
JointPose joint_pose_of(double flexion_deg, const Vector5d& q);

class FreePose {
public:
  FreePose(const JointCoordinateSystem& jcs, double flexion_deg, const Vector5d& q);

  /// The femur's motion from its rest pose.
  const Eigen::Isometry3d& motion() const { return m_motion; }
  /// Where femur point X (rest, mm) goes.
  Eigen::Vector3d point(const Eigen::Vector3d& X) const { return m_motion * X; }
  /// d point / d q (3 x 5).
  Matrix35d jacobian(const Eigen::Vector3d& X) const;
  /// sum_m w_m d^2 point_m / (d q_k d q_l), the 5 x 5 second derivative of w . point(X).
  Matrix5d weighted_second(const Eigen::Vector3d& X, const Eigen::Vector3d& w) const;
  /// The motion's rotation L (point = L X + shift) and dL/dq_k (zero for the translations).
  const Eigen::Matrix3d& rotation() const { return m_Rt; }
  Eigen::Matrix3d rotation_derivative(int k) const
  {
    return k < 2 ? m_dRt[static_cast<std::size_t>(k)] : Eigen::Matrix3d::Zero();
  }

private:
  Eigen::Isometry3d m_motion;
  Eigen::Vector3d m_origin;
  Eigen::Matrix3d m_axes; ///< columns e1, e2, e3 (rest)
  double m_side = 1.0;
  /// R^T and its derivatives: dRt[0] = d/dvarus, dRt[1] = d/dinternal; ddRt[k][l].
  Eigen::Matrix3d m_Rt;
  std::array<Eigen::Matrix3d, 2> m_dRt;
  std::array<std::array<Eigen::Matrix3d, 2>, 2> m_ddRt;
};

} // namespace ligsim::sim
