#pragma once
/// @brief `ligsim flexion` with the femur free: the knee's own path found at every angle
/// (free_femur.hpp), then the sweep along it as along any path, so that every output of a
/// prescribed sweep comes the same way; and kinematics.csv, what the knee did.

#include "sim/flexion/articular_contact.hpp"
#include "sim/flexion/free_femur.hpp"
#include "sim/flexion/knee_flexion.hpp"
#include "sim/flexion/knee_model.hpp"
#include "sim/flexion/knee_motion.hpp"

#include <filesystem>
#include <optional>
#include <utility>
#include <vector>

namespace ligsim::sim {

struct FreeFlexion {
  FreeFemurResult found;
  /// `motion` with the path the knee found (a table of its poses by flexion angle); when the
  /// search stopped, the angles it reached.
  KneeMotion motion;
  /// Where the articular layers met per compartment (with articular contact).
  std::optional<ArticularContact::Seat> seat;
  /// Each ligament's equilibrium at the angles of `motion`, by name: where its sweep along the
  /// found path starts each angle.
  EquilibriumGuesses equilibria;
};

/// Whether the knee flexes free by default ([motion] path = "auto"): it has both collateral and
/// both cruciate ligaments (by name) and its femur and tibia.
bool flexes_free_by_default(const std::vector<LigamentModel>& ligaments);

/// Makes `[motion] path = "auto"` free when `whole` (the knee's every ligament) flexes free by
/// default, saying so on stderr; true when the path is free.
bool choose_free_path(FlexionSettings& settings, const std::vector<LigamentModel>& whole);

/// The ligaments that hold the femur on its free path: the whole knee's but those cut
/// (`--without`), whichever of them are swept.
std::vector<LigamentModel> free_path_ligaments(const std::vector<LigamentModel>& whole,
                                               const FlexionSettings& settings);

/// Finds the free path of `ligaments` (with `settings`' loads and articular contact, the bones'
/// grids in `contact_cache`) at `motion`'s angles in its joint coordinate system.
FreeFlexion find_free_flexion(const std::vector<LigamentModel>& ligaments, const KneeMotion& motion,
                              const FlexionSettings& settings,
                              const std::filesystem::path& contact_cache);

/// kinematics.csv: per angle the tibia's Grood & Suntay coordinates relative to the femur
/// (angle_deg, varus_deg, internal_rotation_deg, anterior_mm, medial_mm, proximal_mm), the medial
/// and lateral contact forces and their centres on the tibia (anterior and medial of the JCS
/// origin, mm), and the femur's residual force and moment. Written atomically.
void write_kinematics_csv(const FreeFemurResult& found, const JointCoordinateSystem& jcs,
                          const std::filesystem::path& file);

/// kinematics.svg: the found varus and internal rotation against flexion, beside the passive
/// cadaver knee's mean path (Walker et al., J Biomech 1988;21:965: sim/kinematics/knee_path.hpp).
void write_kinematics_plot(const FreeFemurResult& found, const std::filesystem::path& file);

/// Where a contact centre on the tibia lies from the JCS origin: anterior and medial, mm (NaN
/// for a centre that is not finite).
std::pair<double, double> on_tibia(const Eigen::Vector3d& point, const JointCoordinateSystem& jcs);

} // namespace ligsim::sim
