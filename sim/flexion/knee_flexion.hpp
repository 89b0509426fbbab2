#pragma once
/// @brief The knee flexion sweep on a built model (ligament paper, sec. 4.2 and 5.2): the tibia
/// is fixed, the femur turns about the flexion axis and carries its attachment nodes rigidly;
/// the ligament, pre-stretched along its fibers, follows in equilibrium (quasi-static) or by
/// implicit Euler frames (interactive).

#include "sim/flexion/axis/condyle_axis.hpp"
#include "sim/flexion/flexion_settings.hpp"
#include "sim/flexion/initial_overlap.hpp"
#include "sim/flexion/knee_contact.hpp"
#include "sim/flexion/knee_model.hpp"
#include "sim/flexion/knee_motion.hpp"
#include "sim/flexion/ligament_length.hpp"
#include "sim/flexion/regional_strain.hpp"
#include "sim/solver/boundary_conditions.hpp"
#include "sim/solver/hyperelastic_body.hpp"
#include "sim/solver/implicit_euler.hpp"

#include <Eigen/Core>

#include <cmath>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace ligsim::sim {

/// Constraint set "tibia" held fixed, set "femur" moved by `femur`.
BoundaryConditions knee_conditions(const KneeModel& model, const RigidMotion& femur);
/// The same with the femur turned about `axis` by `last_angle_deg` at load factor 1.
BoundaryConditions knee_conditions(const KneeModel& model, const FlexionAxis& axis,
                                   double last_angle_deg);

/// The steps of a sweep: per step the flexion angle, the load factor and, for a motion in time,
/// the time (else empty).
struct SweepSteps {
  std::vector<double> angles_deg;
  std::vector<double> load_factors;
  std::vector<double> times_s;
  /// Guesses of the equilibrium at each angle (empty: none), solved from first.
  std::vector<Eigen::VectorXd> starts;
};
/// Each ligament's equilibrium at each angle of a sweep, by the ligament's name.
using EquilibriumGuesses = std::map<std::string, std::vector<Eigen::VectorXd>>;

/// Steps at the angles, load factor = angle / last angle.
SweepSteps angle_steps(const std::vector<double>& angles_deg);
/// The steps of a resolved knee motion.
SweepSteps motion_steps(const KneeMotion& motion);

/// The implicit Euler settings of the interactive mode ([interactive]) at `time_step_s`.
DynamicsSettings interactive_dynamics(const FlexionSettings& settings, double time_step_s);

/// Fiber stretch |F a| (with the in-situ pre-stretch) and volume change over the elements.
struct FiberMeasures {
  double mean_fiber_stretch = 0.0; ///< weighted by rest volume
  double max_fiber_stretch = 0.0;
  double min_j = INFINITY;
  /// Share of the rest volume whose fiber strain (stretch - 1) exceeds the failure strain.
  double failed_volume_fraction = 0.0;
  /// The largest regional mean of the fiber stretch (NaN without regions).
  double max_regional_fiber_stretch = NAN;
};

/// The fiber measures of state `x` (flat positions, mm), with the share beyond
/// `failure_strain` and, given `regions`, the largest regional mean.
FiberMeasures measure_fibers(const HyperelasticBody& body, const Eigen::VectorXd& x,
                             double failure_strain = INFINITY,
                             const RegionalMean* regions = nullptr);

/// Regions of `radius_mm` about each element of `body` (rest centroids, rest volumes).
RegionalMean element_regions(const HyperelasticBody& body, double radius_mm);

/// The state at one angle of the sweep.
/// A figure's estimated discretisation error at an angle (error_estimate.hpp); NaN: none.
struct AngleError {
  double femur_force_n = NAN;         ///< of |femur_force_n|
  double regional_fiber_strain = NAN; ///< of the max regional fiber strain (stretch - 1)
};

struct AngleResult {
  double angle_deg = 0.0;
  double load_factor = 0.0;
  double time_s = NAN; ///< a motion in time: the step's time
  bool converged = false;
  double strain_energy_mj = 0.0;
  double max_fiber_stretch = 0.0;  ///< |F a|, with the in-situ pre-stretch
  double mean_fiber_stretch = 0.0; ///< volume-weighted
  /// The largest mean fiber stretch over a region of the ligament settings' radius: the peak
  /// that does not depend on the mesh at a footprint's edge (regional_strain.hpp).
  double max_regional_fiber_stretch = NAN;
  /// Share of the ligament's volume whose fiber strain (stretch - 1) exceeds the ligament's
  /// failure strain.
  double failed_volume_fraction = 0.0;
  /// The centerline's length from footprint to footprint, and its change from the first step at
  /// 0 degrees (else from the built shape); NaN without a centerline.
  double length_mm = NAN;
  double length_change_mm = NAN;
  double length_change_pct = NAN;
  Eigen::Vector3d femur_force_n =
      Eigen::Vector3d::Zero(); ///< what the femur exerts on the ligament
  Eigen::Vector3d tibia_force_n = Eigen::Vector3d::Zero();
  int newton_iterations = 0; ///< quasi-static: Newton iterations; interactive: linear solves
  int substeps = 0;
  /// Newton steps shifted past a buckling point (sim/solver/static_solver); 0 on a smooth path
  int shifted_iterations = 0;
  double relative_residual = 0.0;
  double min_j = 1.0;
  double wall_s = 0.0; ///< since the previous angle
  int frame = -1;      ///< interactive: the frame that reached this angle
  /// With contact: per bone, and per node the gap (mm) and the contact pressure (MPa).
  std::vector<BoneContact> contact;
  Eigen::VectorXd gap_mm;
  Eigen::VectorXd pressure_mpa;
  AngleError error; ///< from a companion solve, when the flexion ran one
};

/// What `bone` exerts on the ligament through its footprint (`footprint_n`: the angle's
/// femur_force_n or tibia_force_n) and by contact together: minus the ligament's whole pull on
/// the bone, the in-situ force a robot's superposition measures. Beside a footprint the two can
/// cancel: an atlas ligament segmented into its bone is pushed out beside its bound rim, and the
/// rim's reaction holds that contact.
Eigen::Vector3d net_force(const AngleResult& angle, const std::string& bone,
                          const Eigen::Vector3d& footprint_n);

/// net_force on the femur.
Eigen::Vector3d femur_net_force(const AngleResult& angle);

struct SweepResult {
  bool success = false;
  std::string failure;
  std::vector<AngleResult> angles;
  double unrelaxed_energy_mj = 0.0; ///< the pre-stretched model before any equilibrium
  OverlapReport overlap;            ///< the ligament's overlap with the bones, and its push
  double wall_s = 0.0;
  // Interactive mode only.
  int frames = 0;
  double time_step_s = 0.0;
  double frames_per_second = 0.0; ///< frames over the time of the frames alone
};

/// Called for each angle reached, with the body swept (the given one, or the one whose rest shape
/// is the reshaped overlap push: ContactConfig::reshape_overlap) and the positions (flat, mm).
using AngleCallback =
    std::function<void(const AngleResult&, const HyperelasticBody& body, const Eigen::VectorXd& x)>;

/// Sweeps `steps` (default: the angles of `settings`, load factor = angle / last angle) in
/// `conditions`, with ligament-bone contact when `contact` is given and settings.contact does not
/// turn it off (then `contact` only measures gaps and penetration). Never throws on divergence:
/// the result says where it stopped.
/// With `centerline`, each angle gets the ligament's length.
SweepResult run_flexion_sweep(const HyperelasticBody& body, const BoundaryConditions& conditions,
                              const FlexionSettings& settings, const AngleCallback& on_angle,
                              const KneeContact* contact = nullptr,
                              const SweepSteps* steps = nullptr,
                              const EmbeddedPolyline* centerline = nullptr);

} // namespace ligsim::sim
