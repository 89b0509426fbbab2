#pragma once
/// @brief Published defaults of the knee's four main ligaments, chosen by the ligament's name in a
/// knee config: the Weiss material and where the ligament fails (docs/knee-model.md cites each).

#include "pipeline/stage_graph/build_config.hpp"

#include <optional>
#include <string>

namespace ligsim::pipeline {

struct LigamentDefaults {
  MaterialDefaults material;
  std::string material_source;
  double failure_strain = 0.171; ///< fiber strain (stretch - 1)
  double failure_load_n = 799.0;
  std::string failure_source;
};

/// The defaults of "MCL", "LCL", "ACL" or "PCL" (any case); none for another name.
std::optional<LigamentDefaults> ligament_defaults(const std::string& name);

} // namespace ligsim::pipeline
