#include "sim/kinematics/free_pose.hpp"

#include <cmath>

namespace ligsim::sim {

namespace {

constexpr double degree = M_PI / 180.0;

Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& a)
{
  Eigen::Matrix3d m;
  m << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return m;
}

} // namespace

Vector5d free_coordinates(const JointPose& pose)
{
  Vector5d q;
  q << pose.varus_deg * degree, pose.internal_rotation_deg * degree, pose.lateral_mm,
      pose.anterior_mm, pose.proximal_mm;
  return q;
}

JointPose joint_pose_of(double flexion_deg, const Vector5d& q)
{
  JointPose pose;
  pose.flexion_deg = flexion_deg;
  pose.varus_deg = q(0) / degree;
  pose.internal_rotation_deg = q(1) / degree;
  pose.lateral_mm = q(2);
  pose.anterior_mm = q(3);
  pose.proximal_mm = q(4);
  return pose;
}

FreePose::FreePose(const JointCoordinateSystem& jcs, double flexion_deg, const Vector5d& q)
    : m_motion(femur_motion(jcs, joint_pose_of(flexion_deg, q)))
    , m_origin(jcs.origin_mm)
    , m_axes(joint_axes(jcs))
    , m_side(jcs.side >= 0 ? 1.0 : -1.0)
{
  const Eigen::Vector3d e1 = m_axes.col(0), e2 = m_axes.col(1), e3 = m_axes.col(2);
  const Eigen::Matrix3d At =
      Eigen::AngleAxisd(-flexion_deg * degree, e1).toRotationMatrix().transpose();
  const Eigen::Matrix3d Bt = Eigen::AngleAxisd(m_side * q(0), e2).toRotationMatrix().transpose();
  const Eigen::Matrix3d Ct = Eigen::AngleAxisd(m_side * q(1), e3).toRotationMatrix().transpose();
  // R^T = C^T B^T A^T; d(B^T)/d varus = -side [e2]x B^T, d(C^T)/d internal = -side [e3]x C^T.
  const Eigen::Matrix3d X2 = cross_matrix(e2), X3 = cross_matrix(e3);
  m_Rt = Ct * Bt * At;
  m_dRt[0] = -m_side * Ct * X2 * Bt * At;
  m_dRt[1] = -m_side * X3 * Ct * Bt * At;
  m_ddRt[0][0] = Ct * X2 * X2 * Bt * At;
  m_ddRt[1][1] = X3 * X3 * Ct * Bt * At;
  m_ddRt[0][1] = m_ddRt[1][0] = X3 * Ct * X2 * Bt * At;
}

Matrix35d FreePose::jacobian(const Eigen::Vector3d& X) const
{
  // x = R^T (X - O) + O - v, v = side L e1 + A e2 + P e3.
  Matrix35d J;
  J.col(0) = m_dRt[0] * (X - m_origin);
  J.col(1) = m_dRt[1] * (X - m_origin);
  J.col(2) = -m_side * m_axes.col(0);
  J.col(3) = -m_axes.col(1);
  J.col(4) = -m_axes.col(2);
  return J;
}

Matrix5d FreePose::weighted_second(const Eigen::Vector3d& X, const Eigen::Vector3d& w) const
{
  Matrix5d H = Matrix5d::Zero(); // the translations enter linearly
  for (int k = 0; k < 2; ++k)
    for (int l = 0; l < 2; ++l)
      H(k, l) = w.dot(m_ddRt[k][l] * (X - m_origin));
  return H;
}

} // namespace ligsim::sim
