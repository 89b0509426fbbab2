#pragma once
/// @brief A load step's report as JSON: every figure of StepReport under its own name, once,
/// for every writer of a step (a scene's summary.json, ...).

#include "sim/solver/static_solver.hpp"

#include <nlohmann/json.hpp>

namespace ligsim::sim {

/// The step's figures; `floor` and `instability` only where they say something.
nlohmann::json to_json(const StepReport& step);

} // namespace ligsim::sim
