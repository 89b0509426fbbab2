#pragma once
/// @brief Each config's settings as summary.json's `parameters.config`: every key of its settings
/// tables with the value the run used, written from the same key lists its reader walks
/// (sim/flexion/flexion_fields.hpp, sim/scene/scene_fields.hpp,
/// sim/membrane/scene/scene_fields.hpp).

#include "sim/flexion/flexion_settings.hpp"
#include "sim/membrane/scene/scene.hpp"
#include "sim/scene/scene.hpp"

#include <nlohmann/json.hpp>

namespace ligsim::reports {

/// A flexion config: {"angles_deg": ..., "axis": {...}, ...}, with the model and the motion table.
nlohmann::json to_json(const sim::FlexionSettings& settings);
/// A scene: {"material": {...}, "solver": {...}, ...}.
nlohmann::json to_json(const sim::Scene& scene);
/// A tear scene: {"material": {...}, "tearing": {...}, ...}.
nlohmann::json to_json(const membrane::Scene& scene);

} // namespace ligsim::reports
