#pragma once
/// @brief The knee's side and its landmarks found on its bones, each with how it was found.
///
/// Epicondyles: the most prominent points of the condyles along the flexion axis. Where the
/// condyle's side is flat to within a few millimetres over a large area (as on an atlas' hand-made
/// femur), "most prominent" spans that whole face: the point of it taken is the one nearest the
/// femoral end of the collateral ligament that attaches there, when the knee has it (the
/// collaterals insert a few millimetres from their epicondyles: LaPrade et al., J Bone Joint
/// Surg Am 2007;89:2000, Am J Sports Med 2003;31:854), else its centroid.

#include "common/mesh.hpp"

#include <Eigen/Core>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace ligsim::anatomy {

struct Landmark {
  Eigen::Vector3d point_mm = Eigen::Vector3d::Zero();
  std::string how; ///< one line: how it was found
};

/// The knee's side from the parts that lie lateral (the fibula, the LCL) or medial (the MCL) of
/// the tibial plateau's centre, with the subject's right = anterior x proximal.
struct SideFinding {
  std::string side;                  ///< "left", "right", or empty when nothing tells
  std::vector<std::string> evidence; ///< one line per part that told (or contradicted)
  bool contradicted = false;         ///< parts disagree: the side is left empty
};

/// A part's centroid, and whether it lies on the medial (MCL) or the lateral side (fibula, LCL).
struct SidePart {
  std::string name;
  Eigen::Vector3d centroid_mm;
  bool medial = false;
};

/// @param plateau_centre_mm the tibial plateau's centre; proximal, posterior unit
SideFinding side_from_parts(const std::vector<SidePart>& parts,
                            const Eigen::Vector3d& plateau_centre_mm,
                            const Eigen::Vector3d& proximal, const Eigen::Vector3d& posterior);

/// The flexion axis the femur's landmarks are measured from: a cylinder fitted to the posterior
/// condyles, `medial` its unit direction toward the medial condyle.
struct CondyleCylinder {
  Eigen::Vector3d point_mm = Eigen::Vector3d::Zero();
  Eigen::Vector3d medial = Eigen::Vector3d::UnitX();
  double radius_mm = 20.0;
};

/// "medial_epicondyle", "lateral_epicondyle", "intercondylar_notch". `mcl` and `lcl` (may be
/// null) choose among a flat face's points (above).
std::map<std::string, Landmark> femur_landmarks(const TriangleSurface& femur,
                                                const CondyleCylinder& axis,
                                                const Eigen::Vector3d& proximal,
                                                const TriangleSurface* mcl,
                                                const TriangleSurface* lcl);

/// "tibial_plateau_centre", "medial_tibial_plateau", "lateral_tibial_plateau": the centroids of
/// the plateau's upward-facing surface (its proximal 12 mm), whole and on each side of the
/// centre along `medial`.
std::map<std::string, Landmark> tibia_landmarks(const TriangleSurface& tibia,
                                                const Eigen::Vector3d& proximal,
                                                const Eigen::Vector3d& medial);

/// "fibular_head": the centroid of the fibula's proximal 10 mm.
std::optional<Landmark> fibular_head(const TriangleSurface& fibula,
                                     const Eigen::Vector3d& proximal);

} // namespace ligsim::anatomy
