#pragma once
/// @brief The knee's anatomical directions read off its bones, for data whose frame does not
/// say them (surfaces, or a label map made from an atlas' surfaces).
///
/// Proximal: from the tibia's centroid to the femur's. Mediolateral: the long axis of the tibial
/// plateau (its proximal 15 mm, about 75 x 50 mm in adults), across proximal. Posterior: across
/// both, its sign from the cues the bones give: the patella lies in front of the femur's distal
/// end, the femoral condyles behind the femoral shaft, the fibular head behind the plateau's
/// centre. Each cue is reported with its size; they must agree.

#include "common/mesh.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace ligsim::anatomy {

/// The bones there are (null: not given).
struct KneeBones {
  const TriangleSurface* femur = nullptr;
  const TriangleSurface* tibia = nullptr;
  const TriangleSurface* fibula = nullptr;
  const TriangleSurface* patella = nullptr;
};

struct BoneDirections {
  Eigen::Vector3d proximal = Eigen::Vector3d::Zero();     ///< unit
  Eigen::Vector3d posterior = Eigen::Vector3d::Zero();    ///< unit, across proximal
  Eigen::Vector3d mediolateral = Eigen::Vector3d::Zero(); ///< unit, sign arbitrary
  std::vector<std::string> evidence;                      ///< one line per finding
};

/// Throws InputError when the femur or the tibia is missing, when no cue tells anterior from
/// posterior, or when the cues disagree.
BoneDirections directions_from_bones(const KneeBones& bones);

} // namespace ligsim::anatomy
