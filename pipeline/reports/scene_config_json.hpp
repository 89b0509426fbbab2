#pragma once
/// @brief A scene's settings as summary.json's `parameters.config`: every settings key of the
/// scene with the value the run used, written from the same key lists the scene's reader walks
/// (sim/scene/scene_fields.hpp).

#include "sim/scene/scene.hpp"

#include <nlohmann/json.hpp>

namespace ligsim::reports {

/// The settings as the scene's tables ({"material": {...}, "solver": {...}, ...}).
nlohmann::json to_json(const sim::Scene& scene);

} // namespace ligsim::reports
