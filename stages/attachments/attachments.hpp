#pragma once
/// @brief The attachment areas A1 (femur) and A2 (tibia) as ligament-surface vertex sets.

#include "common/mesh.hpp"

#include <Eigen/Core>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace ligsim::attachments {

/// How one attachment area is found. `rule`:
///  - "indices":   the vertex indices listed in `indices`;
///  - "array":     the vertices where the surface's point-data array `array` is non-zero;
///  - "proximity": the vertices within `distance_mm` of the bone surface;
///  - "end":       the vertices within `end_length_mm` of one end of the ligament along its main
///                 axis: `end` = "min" or "max" along the axis (oriented towards +z), or "auto":
///                 the end farther from the other attachment, else +z for the femur, -z for the
///                 tibia;
///  - "auto":      indices if given, else array if named, else proximity if the bone surface is
///                 given, else end.
struct Rule {
  std::string rule = "auto";
  std::vector<int> indices;
  std::string array;
  double distance_mm = 1.0;
  double end_length_mm = 5.0;
  std::string end = "auto";
};

struct Area {
  std::vector<int> vertices; ///< sorted ligament-surface vertex indices
  std::string rule;          ///< the rule that produced it, with its parameters, for summary.json
  Eigen::Vector3d mean = Eigen::Vector3d::Zero(); ///< mean position, mm
};

struct Inputs {
  const TriangleSurface* ligament = nullptr;
  const TriangleSurface* femur = nullptr; ///< optional
  const TriangleSurface* tibia = nullptr; ///< optional
  /// Point-data arrays of the ligament surface, by name (for the "array" rule).
  std::map<std::string, Eigen::VectorXd> arrays;
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
