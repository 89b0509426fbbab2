#pragma once
/// @brief The attachment areas A1 (femur) and A2 (tibia) as ligament-surface vertex sets: the
/// footprints where the ligament inserts into its bones (elsewhere it is free and meets the
/// bones by contact).

#include "common/mesh.hpp"

#include <Eigen/Core>

#include <cmath>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace ligsim::attachments {

/// How one attachment area is found. `rule`:
///  - "indices":   the vertex indices listed in `indices`;
///  - "array":     the vertices where the surface's point-data array `array` is non-zero;
///  - "proximity": the vertices within `distance_mm` of the bone surface, or inside it (a closed
///                 bone);
///  - "patch":     the vertices within `distance_mm` of a footprint surface (an enthesis patch,
///                 given to `find` as Inputs::femur_patch / tibia_patch; `patch` names its file);
///  - "landmark":  the vertices within `radius_mm` of a point: `point_mm`, or the anatomy's
///                 landmark called `landmark` (Inputs::landmarks) moved `proximal_mm` up the leg
///                 and `posterior_mm` back (needs Inputs::proximal / posterior when non-zero);
///  - "end":       the vertices within `end_length_mm` of one end of the ligament along its main
///                 axis: `end` = "proximal" or "distal" (needs Inputs::proximal), "min" or "max"
///                 along the axis (oriented towards +z), or "auto": proximal for the femur and
///                 distal for the tibia when the proximal direction is known, else the end
///                 farther from the other attachment, else +z for the femur, -z for the tibia;
///  - "auto":      indices if given, else array if named, else proximity if the bone surface is
///                 given, else end.
/// Any rule but indices and array keeps, when `bone_distance_mm` > 0 and the bone is given, only
/// the vertices within that distance of the bone: the footprint is the side facing the bone.
///
/// A landmark rule with `snap` holds its footprint to the ligament it serves: when the disc's
/// centre misses the ligament (no vertex within the radius), the disc moves to the vertex nearest
/// that centre at the ligament's end toward this bone (proximal for the femur, distal for the
/// other); when the anatomy lacks the landmark, the footprint is that end. Then, for any rule, a
/// footprint farther than `max_distance_mm` from its landmark is refused, and one larger than
/// `max_area_mm2` has its disc shrunk until it fits (a rule without a disc is refused): both say
/// what was found and what to give.
struct Rule {
  std::string rule = "auto";
  std::vector<int> indices;
  std::string array;
  double distance_mm = 1.0;
  double end_length_mm = 5.0;
  std::string end = "auto";
  std::string patch;    ///< file of the footprint surface ("patch"; read by the caller)
  std::string landmark; ///< anatomy landmark name ("landmark")
  Eigen::Vector3d point_mm = Eigen::Vector3d::Constant(NAN); ///< "landmark", when no name
  double radius_mm = 5.0;                                    ///< "landmark"
  double proximal_mm = 0.0;  ///< "landmark": offset up the leg from the landmark
  double posterior_mm = 0.0; ///< "landmark": offset toward posterior
  double bone_distance_mm = 0.0;
  bool snap = false;            ///< "landmark": move to the ligament when its centre misses it
  double max_distance_mm = 0.0; ///< "landmark": farthest the footprint may lie from it; 0: any
  double max_area_mm2 = 0.0;    ///< largest footprint (Area::area_mm2); 0: any
};

struct Area {
  std::vector<int> vertices; ///< sorted ligament-surface vertex indices
  std::string rule;          ///< the rule that produced it, with its parameters, for summary.json
  Eigen::Vector3d mean = Eigen::Vector3d::Zero(); ///< mean position, mm
  double area_mm2 = 0.0;  ///< ligament surface in the footprint: triangles weighted by the share
                          ///< of their corners in it
  double extent_mm = 0.0; ///< largest distance between two of its vertices
  std::vector<std::string> corrections; ///< what a snap or a published bound changed
};

struct Inputs {
  const TriangleSurface* ligament = nullptr;
  const TriangleSurface* femur = nullptr; ///< optional
  const TriangleSurface* tibia = nullptr; ///< optional
  /// Point-data arrays of the ligament surface, by name (for the "array" rule).
  std::map<std::string, Eigen::VectorXd> arrays;
  const TriangleSurface* femur_patch = nullptr; ///< "patch" rules
  const TriangleSurface* tibia_patch = nullptr;
  std::map<std::string, Eigen::Vector3d> landmarks; ///< "landmark" rules, mm
  std::optional<Eigen::Vector3d> proximal;          ///< unit, up the leg: "end" rules
  std::optional<Eigen::Vector3d> posterior;         ///< unit: "landmark" offsets
};

struct Attachments {
  Area femur; ///< A1
  Area tibia; ///< A2
};

/// Resolves both areas. Throws InputError when an area is empty, when the two overlap, or when a
/// rule lacks what it needs (a bone surface, an array, valid indices).
Attachments find(const Inputs& inputs, const Rule& femur, const Rule& tibia);

/// The main axis of the points (largest principal direction), oriented so that z >= 0.
Eigen::Vector3d main_axis(const Points& points);

} // namespace ligsim::attachments
