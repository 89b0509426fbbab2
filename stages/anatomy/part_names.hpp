#pragma once
/// @brief What a segment's name means: the knee's bones, ligaments, cartilage and menisci
/// recognised under the names 3D Slicer, ITK-SNAP and the atlases give them
/// (`tibial_collateral_ligament`, `MCL`, `Medial collateral lig.`, `VH_F_femur_L`, ...).

#include <optional>
#include <string>

namespace ligsim::anatomy {

/// A part of the knee ligsim knows by name.
enum class KneePart {
  femur,
  tibia,
  fibula,
  patella,
  mcl, ///< superficial medial (tibial) collateral ligament
  lcl, ///< lateral (fibular) collateral ligament
  acl,
  pcl,
  femoral_cartilage,
  tibial_cartilage, ///< medial, lateral or both plateaus
  patellar_cartilage,
  meniscus, ///< medial, lateral or both
};

/// The part `name` names, if it is one of the knee's: case, separators (`_`, `-`, `.`, spaces),
/// the side (`left`, `R`, `_L`), words like `bone`, `of`, `knee` and an atlas' `VH_F_` prefix are
/// ignored. Names that mention a part of a part (`medial_condyle_of_femur`,
/// `lateral_epicondylar_enthesis`) or another ligament (`anterolateral_ligament`,
/// `patellar_ligament`) are not recognised.
std::optional<KneePart> recognise_part(const std::string& name);

/// The canonical name: "femur", "MCL", "femoral_cartilage", ...; ligaments in capitals, as a knee
/// config names them.
std::string part_name(KneePart part);

/// Whether `part` is one of the ligaments ligsim builds (MCL, LCL, ACL, PCL).
bool is_ligament(KneePart part);
/// Whether `part` is a bone.
bool is_bone(KneePart part);

} // namespace ligsim::anatomy
