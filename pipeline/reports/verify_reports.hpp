#pragma once
/// @brief The JSON files of `ligsim verify`: the cube against FEBio (verify.json) and the two
/// stability suites (stability.json). The results are typed in sim/verify; JSON is written
/// here, at the edge.

#include "sim/verify/cube_verification.hpp"
#include "sim/verify/flexion_stability.hpp"
#include "sim/verify/stability.hpp"

#include <nlohmann/json.hpp>

#include <vector>

namespace ligsim::reports {

/// verify.json: {"cases": [...]} in the schema, plus our extra figures.
nlohmann::json to_json(const std::vector<sim::CubeCaseResult>& results);

/// The stiff and extreme cube cases: {"cases": [...]}.
nlohmann::json to_json(const std::vector<sim::StabilityResult>& results);

/// The flexion suite's cases, each with its angles as summary.json writes them.
nlohmann::json to_json(const std::vector<sim::FlexionCaseResult>& results);

} // namespace ligsim::reports
