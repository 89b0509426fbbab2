#pragma once
/// @brief What a knee flexion sweep does: the angles, the flexion axis, the material and
/// in-situ strain, quasi-static or interactive, and which pictures to draw (docs/flexion.md).

#include "sim/contact/contact_config.hpp"
#include "sim/flexion/articular_contact.hpp"
#include "sim/material/material_parameters.hpp"
#include "sim/solver/linear_solver.hpp"
#include "sim/solver/static_solver.hpp"

#include <Eigen/Core>

#include <cmath>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

namespace ligsim::sim {

enum class FlexionMode {
  quasi_static, ///< equilibrium at each angle, continuing from the previous one
  interactive,  ///< implicit Euler frames while the femur turns at a constant angular speed
};

/// Where the flexion axis comes from.
struct AxisSettings {
  enum class Source {
    condyles, ///< a cylinder fitted to the femur's posterior condyles (needs `posterior`)
    points,   ///< the line from `first_mm` to `second_mm`; positive angles turn right-handed
    transepicondylar, ///< through the medial and lateral epicondyles
  };
  Source source = Source::condyles;
  Eigen::Vector3d first_mm = Eigen::Vector3d::Zero();
  Eigen::Vector3d second_mm = Eigen::Vector3d::Zero();
  /// The posterior direction in the data's frame (zero: the model's anatomy.json, if any). It
  /// fixes the sign of the fitted axis, so that positive angles flex the knee.
  Eigen::Vector3d posterior = Eigen::Vector3d::Zero();
  /// Transepicondylar: the epicondyles (non-finite: the model's landmarks), mm.
  Eigen::Vector3d medial_epicondyle_mm = Eigen::Vector3d::Constant(NAN);
  Eigen::Vector3d lateral_epicondyle_mm = Eigen::Vector3d::Constant(NAN);
};

/// What the flexion config says of the knee, over what the model's anatomy.json says.
struct AnatomySettings {
  std::string side;                                    ///< "left", "right" or empty
  Eigen::Vector3d proximal = Eigen::Vector3d::Zero();  ///< zero: not given
  Eigen::Vector3d posterior = Eigen::Vector3d::Zero(); ///< zero: not given
};

/// The knee's motion along the sweep.
struct MotionSettings {
  enum class Path {
    automatic, ///< passive when the knee's side is known, else pure flexion (said on stderr)
    pure,      ///< rotation about the flexion axis alone
    passive,   ///< the passive knee's coupled tibial rotations (and translations if asked)
    table,     ///< Grood & Suntay coordinates from a CSV file, per angle or per time
    free,      ///< the femur free in its five other coordinates (FreeKneeSettings)
  };
  Path path = Path::automatic;
  bool coupled_translations = false; ///< passive: the coupled tibial translations as well
  std::filesystem::path table;       ///< the CSV file of `table`
};

/// Loads on the joint, held at every angle (Open Knee(s)' passive flexion: 20 N of compression).
struct JointLoads {
  double compression_n = 20.0; ///< along the tibial axis, pressing the tibia onto the femur
  double anterior_n = 0.0;     ///< on the tibia, anterior (a drawer: negative is posterior)
  double valgus_nm = 0.0;      ///< on the tibia, N m (negative: varus)
  double internal_nm = 0.0;    ///< on the tibia about its axis, N m (negative: external)
};

/// The free knee's solve (sim/flexion/free_femur.hpp).
struct FreeKneeSettings {
  JointLoads loads;
  ArticularSettings articular;
  bool articular_contact = true; ///< femur against tibia (the knee's bones as given)
  double rotation_scale_mm = 20.0;
  /// Converged when the femur's residual force, and its moment over rotation_scale_mm, are below
  /// this share of the largest force on it (a ligament's, the contact's or a load).
  double tolerance = 1e-4;
  int max_iterations = 60;  ///< Newton iterations per angle
  double max_step_mm = 2.0; ///< trust region radius in the scaled unknowns
  /// A coordinate that runs beyond these from the built pose is a load the knee cannot hold.
  double max_translation_mm = 25.0;
  double max_rotation_deg = 60.0;
};

/// The ligament the model is, and where it fails (plausibility warnings per angle).
struct LigamentSettings {
  std::string name = "MCL";
  /// Human MCL failure strain, 17.1 +- 1.5 % (Quapp & Weiss, J Biomech Eng 1998;120:757).
  double failure_strain = 0.171;
  /// MCL load to failure, 799 +- 209 N (Wilson et al., J Orthop Sports Phys Ther 2012).
  double failure_load_n = 799.0;
  /// Radius of the regions of the regional peak fiber strain, mm: experiments measure strain
  /// between surface markers a few millimetres apart (18 regions of the superficial MCL in Lujan
  /// et al., J Biomech Eng 2007, doi:10.1115/1.2720915).
  double strain_region_radius_mm = 2.0;
};

struct InteractiveSettings {
  double angular_speed_deg_s = 45.0;
  double time_step_s = 0.01;
  double density_kg_m3 = 1100.0;
  double mass_damping_per_s = 10.0; ///< Rayleigh alpha
  LinearSolverKind linear_solver = LinearSolverKind::direct;
  /// Linear solves per frame at most (DynamicsSettings::max_iterations): Newton goes on while a
  /// frame's implicit Euler equation is off by more than `iteration_tolerance` of the supports'
  /// force. 1: the paper's one solve per frame.
  int max_iterations = 12;
  double iteration_tolerance = 0.03;
};

struct FlexionSettings {
  std::filesystem::path model_dir; ///< the output folder of `ligsim build`
  std::vector<double> angles_deg = {0, 15, 30, 45, 60, 75, 90};
  FlexionMode mode = FlexionMode::quasi_static;
  AxisSettings axis;
  AnatomySettings anatomy;
  MotionSettings motion;
  LigamentSettings ligament;
  MaterialParameters material = mcl_material();
  /// Fiber pre-stretch of the reference state, sec. 2.7: |a| = 1 + in_situ_strain. It
  /// replaces the strain the model was built with.
  double in_situ_strain = 0.029;
  NewtonSettings newton;
  InteractiveSettings interactive;
  FreeKneeSettings free;
  /// Ligament-bone contact; on by default (the model has both bones).
  ContactConfig contact;
  bool images = true;
  /// The angles drawn as PNG (those of them in the sweep).
  std::vector<double> image_angles_deg = {0, 45, 90};
  /// The ligaments of a knee model to sweep, by name (empty: all of them).
  std::vector<std::string> ligaments;
  /// The ligaments cut (sectioned): the knee flexes or is tested without them.
  std::vector<std::string> without;
  /// What the config or the flags set rather than left at its default: "material",
  /// "in_situ_strain", "ligament.name", "ligament.failure_strain", "ligament.failure_load_n". A
  /// knee model takes each ligament's own values (knee.json) for what is not given.
  std::set<std::string> given;
};

/// Throws InputError naming the first setting that cannot work (empty or unordered angles,
/// a zero-length axis, a non-positive speed or time step, a bad material).
void validate(const FlexionSettings& settings);

std::string to_string(FlexionMode mode);
std::string to_string(AxisSettings::Source source);
std::string to_string(MotionSettings::Path path);

} // namespace ligsim::sim
