/// The femur's pose as a function of the knee's five free coordinates: the motion is
/// femur_motion's, and the first and second derivatives of a femur point match central
/// differences.

#include "sim/kinematics/free_pose.hpp"

#include <gtest/gtest.h>

using namespace ligsim::sim;

namespace {

JointCoordinateSystem jcs(int side)
{
  JointCoordinateSystem j;
  j.origin_mm = Eigen::Vector3d(3.0, -2.0, 40.0);
  j.flexion_axis = side > 0 ? Eigen::Vector3d(1.0, 0.1, -0.05) : Eigen::Vector3d(-1.0, 0.1, 0.05);
  j.tibial_axis = Eigen::Vector3d(0.05, -0.1, 1.0);
  j.side = side;
  return j;
}

} // namespace

TEST(FreePose, ItsMotionIsTheJointPosesAndItsDerivativesAreExact)
{
  for (const int side : {+1, -1})
    for (const double flexion : {0.0, 37.0, 110.0}) {
      Vector5d q;
      q << 0.04, -0.21, 1.3, -2.2, 0.7;
      const FreePose pose(jcs(side), flexion, q);
      const Eigen::Isometry3d expected = femur_motion(jcs(side), joint_pose_of(flexion, q));
      EXPECT_LT((pose.motion().matrix() - expected.matrix()).norm(), 1e-12);
      // Round trip through the JCS's own reading of a pose.
      const Vector5d back = free_coordinates(joint_pose(jcs(side), pose.motion()));
      EXPECT_LT((back - q).norm(), 1e-9);

      const Eigen::Vector3d X(21.0, -13.0, 55.0), w(0.3, -1.2, 0.8);
      const Matrix35d J = pose.jacobian(X);
      const Matrix5d H = pose.weighted_second(X, w);
      const double h = 1e-5;
      for (int k = 0; k < 5; ++k) {
        Vector5d plus = q, minus = q;
        plus(k) += h;
        minus(k) -= h;
        const FreePose p(jcs(side), flexion, plus), m(jcs(side), flexion, minus);
        const Eigen::Vector3d numeric = (p.point(X) - m.point(X)) / (2.0 * h);
        EXPECT_LT((J.col(k) - numeric).norm(), 1e-7) << "side " << side << " k " << k;
        // d/dq_k of w . J: the k-th row of the weighted second derivative.
        const Eigen::Matrix<double, 1, 5> row =
            (w.transpose() * (p.jacobian(X) - m.jacobian(X))) / (2.0 * h);
        EXPECT_LT((H.row(k) - row).norm(), 1e-7) << "side " << side << " k " << k;
      }
      EXPECT_LT((H - H.transpose()).norm(), 1e-12);
    }
}
