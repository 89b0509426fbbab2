#pragma once
/// @brief The knee's joint coordinate system of Grood & Suntay (J Biomech Eng 1983;105:136):
/// flexion about an axis fixed in the femur (e1), internal/external rotation about the tibia's
/// long axis (e3), varus/valgus about the floating axis e2 = e3 x e1, and three translations.
/// The tibia stays fixed; what moves is the femur, by the inverse of the tibia's motion relative
/// to it.
///
/// The coordinates are those of the tibia relative to the femur, measured from the pose the
/// model was built in (all zero there). The rotation is the Cardan sequence the JCS equals:
/// R = R(e1, -flexion) R(e2, side varus) R(e3, side internal), with the axes at rest and
/// side = +1 for a right knee, -1 for a left one, so that each name keeps its clinical meaning
/// on both sides: flexion swings the tibia posteriorly, varus moves its distal end medially,
/// internal rotation turns its anterior face medially. The translation of the tibia is
/// lateral L + anterior A + proximal P in the tibia's own (turned) axes.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace ligsim::sim {

/// Where the knee's joint coordinate system sits in the model's frame (mm).
struct JointCoordinateSystem {
  Eigen::Vector3d origin_mm = Eigen::Vector3d::Zero(); ///< on the flexion axis
  /// e1, unit, fixed in the femur; turning the femur positively about it flexes the knee (so it
  /// points laterally in a right knee and medially in a left one).
  Eigen::Vector3d flexion_axis = Eigen::Vector3d::UnitX();
  Eigen::Vector3d tibial_axis = Eigen::Vector3d::UnitZ(); ///< e3, unit, fixed in the tibia, up
  int side = +1;                                          ///< +1 right knee, -1 left knee
};

/// Grood & Suntay coordinates of the tibia relative to the femur, from the rest pose.
struct JointPose {
  double flexion_deg = 0.0;
  double varus_deg = 0.0;             ///< adduction of the tibia; negative: valgus
  double internal_rotation_deg = 0.0; ///< of the tibia; negative: external
  double lateral_mm = 0.0;            ///< shift of the tibia toward the knee's lateral side
  double anterior_mm = 0.0;           ///< anterior drawer of the tibia
  double proximal_mm = 0.0;           ///< compression (toward the femur); negative: distraction
};

/// The JCS's rest axes: e1, the floating axis e2 (anterior) and e3 made perpendicular to e1.
/// Throws InputError when the two axes are (nearly) parallel or not finite.
Eigen::Matrix3d joint_axes(const JointCoordinateSystem& jcs);

/// The femur's rigid motion from its rest pose (tibia fixed) that puts the knee in `pose`.
Eigen::Isometry3d femur_motion(const JointCoordinateSystem& jcs, const JointPose& pose);

/// The coordinates of a femur motion (the inverse of femur_motion, for checks and outputs).
JointPose joint_pose(const JointCoordinateSystem& jcs, const Eigen::Isometry3d& femur_motion);

} // namespace ligsim::sim
