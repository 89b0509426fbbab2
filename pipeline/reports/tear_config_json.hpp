#pragma once
/// @brief A tear scene's settings as summary.json's `parameters.config`: every key of its
/// settings tables with the value the run used, written from the same key lists the scene's
/// reader walks (sim/membrane/scene/scene_fields.hpp).

#include "sim/membrane/scene/scene.hpp"

#include <nlohmann/json.hpp>

namespace ligsim::reports {

/// The settings as the scene's tables ({"material": {...}, "tearing": {...}, ...}).
nlohmann::json to_json(const membrane::Scene& scene);

} // namespace ligsim::reports
