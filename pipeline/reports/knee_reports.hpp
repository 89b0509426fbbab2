#pragma once
/// @brief summary.json's entries for what a knee flexion reports besides its angles: the push
/// out of the bones before the sweep, the free knee's path, the ligaments' pairs, their
/// footprints and cross-sections. The results are typed in sim/; JSON is written here, at the
/// edge.

#include "sim/flexion/error_estimate.hpp"
#include "sim/flexion/free_flexion.hpp"
#include "sim/flexion/initial_overlap.hpp"
#include "sim/flexion/knee_flexion.hpp"
#include "sim/flexion/knee_motion.hpp"
#include "sim/flexion/knee_sweep.hpp"
#include "sim/flexion/ligament_pairs.hpp"
#include "sim/flexion/plausibility.hpp"
#include "sim/kinematics/joint_coordinates.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace ligsim::reports {

/// One angle of a sweep (summary.json's per-angle entries).
nlohmann::json to_json(const sim::AngleResult& angle);

/// A ligament's companion solve: the mesh, the size ratio, its time and how the error is
/// estimated.
nlohmann::json to_json(const sim::CompanionSweep& companion);

/// How the flexion axis was found: the two points, the condyle fit's figures, or the epicondyles.
nlohmann::json to_json(const sim::AxisFigures& figures);

/// How the knee's motion was resolved: the other anatomical axis, the tibial axis, the built
/// pose, the side and the path.
nlohmann::json to_json(const sim::MotionFigures& figures);

/// What a ligament's sweep was set up with: nodes, tets, volume, the contact grids.
nlohmann::json to_json(const sim::LigamentSetup& setup);

/// The plausibility warnings, each with its angle.
nlohmann::json to_json(const std::vector<sim::AngleWarning>& warnings);

/// The gaps to each bone before the push and, when pushed, after it and how.
nlohmann::json to_json(const sim::OverlapReport& report);

/// The free knee's path: per angle the tibia's Grood & Suntay coordinates, the articular contact
/// (forces, centres on the tibia in `jcs`, area, peak pressure) and the femur's residual.
nlohmann::json to_json(const sim::FreeFemurResult& found, const sim::JointCoordinateSystem& jcs);

/// Every pair at every angle, with its angle.
nlohmann::json to_json(const std::vector<sim::PairAtAngle>& pairs);

/// The femoral and distal footprints of `ligament`, with the published areas where known.
nlohmann::json footprints_json(const std::vector<sim::Footprint>& prints,
                               const std::string& ligament);

/// How thick `ligament` was built, beside its published cross-section, and the finding when it
/// is too thin.
nlohmann::json thickness_json(const sim::LigamentThickness& thickness, const std::string& ligament);

} // namespace ligsim::reports
