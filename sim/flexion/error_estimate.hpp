#pragma once
/// @brief The discretisation error of a flexion's figures, from a companion solve: the same
/// ligament meshed coarser (built beside the model in its folder's companion/, by
/// pipeline/stage_graph/companion_build), swept through the same motion. The error of each
/// figure is Roache's grid convergence index (J Fluids Eng 1994;116:405; Celik et al., J Fluids
/// Eng 2008;130:078001):
///   GCI = Fs |f_fine - f_coarse| / (r^p - 1),
/// Fs = 3, the safety factor of a two-mesh study (no observed order); p = 2, the order of linear
/// tets in energy and the most the corner at a bound footprint's edge lets either element
/// reach; r the ratio of the meshes' element sizes, (volume / elements)^(1/3). With r = 1.5 the
/// estimate is at least the error for any observed order from 0.9 to 2.75, and at most five
/// times it; a figure converging more slowly than first order (a mesh far from the asymptotic
/// range) can be off by more than the estimate, and so can a family whose meshes lock alike
/// (linear tets in a thin band's bending: the companion shares the model's error).

#include "sim/flexion/knee_sweep.hpp"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace ligsim::sim {

/// One ligament's companion solve.
struct CompanionSweep {
  std::string ligament;
  bool swept = false;
  std::string note; ///< why there is no estimate, or none for some angles; empty: all angles
  std::filesystem::path folder;
  Eigen::Index tets = 0;
  double size_ratio = NAN; ///< r: the companion's element size over the model's
  double wall_s = 0.0;
  int angles_reached = 0;
};

/// Roache's GCI of a figure from the fine and coarse meshes' values and their size ratio r > 1.
double grid_convergence_index(double fine, double coarse, double size_ratio);

/// Above this share of the femur force, linear tets' error estimate is taken as locking's mark.
inline constexpr double kLockingErrorShare = 0.25;

/// What to say when a model of linear tets has an estimated femur-force error above
/// kLockingErrorShare of the force at some angle (`angles` with their errors): the largest share,
/// its angle and the remedy, 10-node tets. Empty for 10-node tets or smaller estimates.
std::string locking_warning(const std::vector<AngleResult>& angles, bool linear_tets);

/// The companion of `ligament` (its folder's companion/ model, with the ligament's bones and
/// anatomy), none when the folder has none. Throws InputError as load_knee_model does.
std::optional<LigamentModel> load_companion(const LigamentModel& ligament);

/// Sweeps each ligament's companion through `motion` with the ligament's settings and gives
/// each angle of `sweeps` (the model's sweep, in the order of `ligaments`) its error
/// (AngleResult::error). A ligament without a companion, or an angle the companion did not
/// reach, gets none; the report says why.
/// Implicit Euler frames sweep linear tets, as the model's did (linear_tets_for_frames).
std::vector<CompanionSweep> estimate_sweep_errors(const std::vector<LigamentModel>& ligaments,
                                                  const KneeMotion& motion,
                                                  const FlexionSettings& settings,
                                                  const std::filesystem::path& contact_cache,
                                                  std::vector<LigamentSweep>& sweeps);

} // namespace ligsim::sim
