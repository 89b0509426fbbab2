#pragma once
/// @brief A flexion's settings as summary.json's `parameters.config`: every key of the flexion
/// config with the value the run used, written from the same key lists the config's reader walks
/// (sim/flexion/flexion_fields.hpp).

#include "sim/flexion/flexion_settings.hpp"

#include <nlohmann/json.hpp>

namespace ligsim::reports {

/// The settings as the config's tables ({"angles_deg": ..., "axis": {...}, ...}).
nlohmann::json to_json(const sim::FlexionSettings& settings);

} // namespace ligsim::reports
