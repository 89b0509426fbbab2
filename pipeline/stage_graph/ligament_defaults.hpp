#pragma once
/// @brief Published defaults of the knee's four main ligaments, chosen by the ligament's name (a
/// knee config's, or a label's recognised by stages/anatomy/part_names): the Weiss material, where
/// the ligament fails and where its footprints lie (docs/knee-model.md cites each).

#include "pipeline/stage_graph/build_config.hpp"

#include <optional>
#include <string>

namespace ligsim::pipeline {

struct LigamentDefaults {
  sim::MaterialParameters material = sim::mcl_material();
  std::string material_source;
  double failure_strain = 0.171; ///< fiber strain (stretch - 1)
  double failure_load_n = 799.0;
  std::string failure_source;
  /// The footprints: on the femur, and on `distal_bone` ("tibia" or "fibula").
  attachments::Rule femur_footprint;
  attachments::Rule distal_footprint;
  std::string distal_bone = "tibia";
  std::string footprint_source;
};

/// The defaults of "MCL", "LCL", "ACL" or "PCL" (any case), or of a name that
/// anatomy::recognise_part takes for one of them ("tibial_collateral_ligament"); none for
/// another name.
std::optional<LigamentDefaults> ligament_defaults(const std::string& name);

} // namespace ligsim::pipeline
