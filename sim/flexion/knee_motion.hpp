#pragma once
/// @brief The knee's motion in a flexion sweep, from the model's anatomy and the flexion
/// settings: the flexion axis (a cylinder fitted to the posterior condyles, the
/// transepicondylar axis, or two points), the Grood & Suntay joint coordinate system on it, the
/// path of its coordinates (pure flexion, the passive knee's coupling, or a CSV table) and the
/// femur's rigid path that a solver follows.

#include "common/knee_anatomy.hpp"
#include "sim/flexion/axis/condyle_axis.hpp"
#include "sim/flexion/flexion_settings.hpp"
#include "sim/flexion/knee_model.hpp"
#include "sim/kinematics/knee_path.hpp"
#include "sim/solver/boundary_conditions.hpp"

#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace ligsim::sim {

/// An axis given as two points.
struct AxisPoints {
  Eigen::Vector3d first_mm = Eigen::Vector3d::Zero();
  Eigen::Vector3d second_mm = Eigen::Vector3d::Zero();
};

/// A cylinder fitted to the posterior condyles: the fit's figures and the directions it used.
struct CondyleFitFigures {
  double radius_mm = 0.0;
  double rms_residual_mm = 0.0;
  double span_mm = 0.0;
  int points_used = 0;
  int points_considered = 0;
  Eigen::Vector3d proximal = Eigen::Vector3d::Zero();
  Eigen::Vector3d posterior_hint = Eigen::Vector3d::Zero();
};

/// The transepicondylar axis: the epicondyles and which way the axis was turned.
struct EpicondylarFigures {
  Eigen::Vector3d medial_epicondyle_mm = Eigen::Vector3d::Zero();
  Eigen::Vector3d lateral_epicondyle_mm = Eigen::Vector3d::Zero();
  double length_mm = 0.0;
  std::string oriented;
};

using AxisFigures = std::variant<AxisPoints, CondyleFitFigures, EpicondylarFigures>;

/// The flexion axis a sweep uses and how it was found.
struct ResolvedAxis {
  FlexionAxis axis;
  std::string method;
  AxisFigures figures; ///< the points, the fit's radius and residual, or the epicondyles
};

/// The other anatomical axis than the one used, for the angle between the two.
struct OtherAxis {
  std::string method;
  std::optional<ResolvedAxis> found;
  double angle_deg = 0.0;    ///< between it and the axis used, where found
  std::string not_available; ///< why not, where not found
};

/// The tibia's long axis and where it came from.
struct TibialAxisFigures {
  std::string source;
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();
  std::optional<double> angle_to_proximal_deg;
};

/// How far the knee was flexed where it was built (Grood & Suntay's flexion of the femoral shaft
/// against the tibia's long axis); the angles a sweep names are counted from it.
struct BuiltPose {
  std::optional<double> flexion_deg; ///< empty: not measured
  Eigen::Vector3d femoral_shaft = Eigen::Vector3d::Zero();
  std::string source;       ///< how it was measured
  std::string not_measured; ///< why not
};

/// How the motion was resolved.
struct MotionFigures {
  std::optional<OtherAxis> other_axis; ///< none for an axis given as two points
  TibialAxisFigures tibial_axis;
  BuiltPose built_pose;
  std::string side;         ///< "left", "right" or "not known"
  std::string frame_source; ///< where the anatomical directions came from
  std::string path;         ///< the path's description
  std::string note;         ///< a fallback the path took, if any
};

/// The model's anatomy with the flexion settings over it ([anatomy], and [axis] posterior);
/// without anatomy.json the proximal direction comes from the bones.
KneeAnatomy effective_anatomy(const KneeModel& model, const FlexionSettings& settings);

/// The axis from two points, fitted to the femur's posterior condyles, or through the
/// epicondyles. Throws InputError saying what to give when the choice lacks its inputs.
ResolvedAxis resolve_flexion_axis(const KneeModel& model, const AxisSettings& settings,
                                  const KneeAnatomy& anatomy);
/// The same with the model's own anatomy.
ResolvedAxis resolve_flexion_axis(const KneeModel& model, const AxisSettings& settings);

/// Everything the femur's motion needs.
struct KneeMotion {
  ResolvedAxis axis;
  JointCoordinateSystem jcs;
  std::shared_ptr<const FemurPath> femur_path;
  /// Per step of the sweep: the flexion angle and, for a motion in time, the time (else empty).
  std::vector<double> angles_deg;
  std::vector<double> times_s;
  std::vector<double> load_factors;
  MotionFigures figures; ///< side, tibial axis, path, the other anatomical axis and its angle
};

/// Resolves the motion of `settings` on `model`. Throws InputError when the path needs the
/// knee's side and it is not known, when a motion in time is asked in interactive mode, or as
/// resolve_flexion_axis does.
KneeMotion resolve_knee_motion(const KneeModel& model, const FlexionSettings& settings);

/// The femur's rigid motion for a solver.
RigidMotion femur_rigid_motion(const KneeMotion& motion);

} // namespace ligsim::sim
