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

#include <nlohmann/json.hpp>

#include <memory>
#include <string>
#include <vector>

namespace ligsim::sim {

/// The flexion axis a sweep uses and how it was found.
struct ResolvedAxis {
  FlexionAxis axis;
  std::string method;
  nlohmann::json figures; ///< the fit's radius and residual, the epicondyles, or the points
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
  nlohmann::json figures; ///< side, tibial axis, path, the other anatomical axis and its angle
};

/// Resolves the motion of `settings` on `model`. Throws InputError when the path needs the
/// knee's side and it is not known, when a motion in time is asked in interactive mode, or as
/// resolve_flexion_axis does.
KneeMotion resolve_knee_motion(const KneeModel& model, const FlexionSettings& settings);

/// The femur's rigid motion for a solver.
RigidMotion femur_rigid_motion(const KneeMotion& motion);

} // namespace ligsim::sim
