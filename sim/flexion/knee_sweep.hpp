#pragma once
/// @brief A knee's ligaments swept together: every ligament a body of its own against the same
/// femur motion, with contact against every bone of the knee. The ligaments do not touch each
/// other in the solve, so each is solved on its own (one ligament at a time gives each
/// ligament's answer); ligament_pairs.hpp measures how close they come.

#include "sim/flexion/knee_contact.hpp"
#include "sim/flexion/knee_flexion.hpp"
#include "sim/flexion/knee_model.hpp"
#include "sim/flexion/knee_motion.hpp"
#include "sim/flexion/plausibility.hpp"

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace ligsim::sim {

/// The flexion settings of one ligament: `settings` with the ligament's name, failure figures,
/// material and in-situ strain from knee.json, except what the config or the flags set
/// (settings.given; a [ligament] table applies to the ligament it names). A one-ligament model
/// takes `settings` as they are. The bones it meets by contact: the config's, else knee.json's.
FlexionSettings ligament_settings(const FlexionSettings& settings, const LigamentModel& ligament);

/// The one ligament of settings.model_dir as `ligsim flexion` runs it, for `export febio` and
/// `verify febio`: its model (load_ligament), and `settings` made its own (ligament_settings: its
/// material, in-situ strain and contact bones, except what the config or the flags set).
KneeModel load_ligament_as_flexed(FlexionSettings& settings, const std::string& job);

/// The ligaments of `all` that settings.ligaments names (all of them when empty). Throws
/// InputError naming an unknown ligament, or a [ligament] table naming none of the knee's.
std::vector<LigamentModel> chosen_ligaments(std::vector<LigamentModel> all,
                                            const FlexionSettings& settings);

/// For implicit Euler frames (the interactive sweep, the live view): the ligaments of 10-node
/// tets become linear tets on their corners (with_linear_tets: implicit Euler needs a positive
/// lumped mass, and the frame rate the smaller system). Returns a line for the log and the
/// summary, empty when nothing changed.
std::string linear_tets_for_frames(std::vector<LigamentModel>& ligaments);

/// What one ligament's sweep was set up with.
struct LigamentSetup {
  int nodes = 0;
  Eigen::Index tets = 0;
  std::size_t femur_nodes = 0;
  std::string distal_bone; ///< "tibia" or "fibula"
  std::size_t distal_nodes = 0;
  double rest_volume_mm3 = 0.0;
  KneeContactFigures contact;
};

/// A plausibility warning at an angle.
struct AngleWarning {
  double angle_deg = 0.0;
  std::string warning;
};

/// One ligament's sweep.
struct LigamentSweep {
  std::string name;
  FlexionSettings settings; ///< its own (ligament_settings)
  SweepResult result;
  std::vector<Footprint> footprints;
  std::optional<LigamentThickness> thickness; ///< none without a centerline
  LigamentSetup setup;
  std::vector<AngleWarning> warnings; ///< plausibility, per angle
};

/// Called for each angle each ligament reaches: the ligament's index, its body, the angle and
/// its positions (flat, mm).
using KneeAngleCallback = std::function<void(std::size_t ligament, const HyperelasticBody& body,
                                             const AngleResult& angle, const Eigen::VectorXd& x)>;

/// Sweeps every ligament through `motion`, one after the other; the bones' contact grids are
/// cached in `contact_cache` (shared by the ligaments). A ligament named in `guesses` starts
/// each angle from its guess there. The plausibility warnings go to stderr unless
/// `log_warnings` is false (a companion solve's; each sweep keeps them). Never throws on
/// divergence: each ligament's result says where it stopped.
std::vector<LigamentSweep> run_knee_sweep(const std::vector<LigamentModel>& ligaments,
                                          const KneeMotion& motion, const FlexionSettings& settings,
                                          const std::filesystem::path& contact_cache,
                                          const KneeAngleCallback& on_angle,
                                          const EquilibriumGuesses& guesses = {},
                                          bool log_warnings = true);

/// The knee's frames per second in interactive mode: every ligament's frame in turn, so the
/// reciprocal of the summed seconds per frame.
double knee_frames_per_second(const std::vector<LigamentSweep>& sweeps);

} // namespace ligsim::sim
