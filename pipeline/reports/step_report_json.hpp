#pragma once
/// @brief A load step's report as JSON: every figure of StepReport under its own name, once,
/// for every writer of a step (a scene's summary.json, ...).

#include "sim/solver/static_solver.hpp"

#include <nlohmann/json.hpp>

namespace ligsim::reports {

/// The step's figures; `floor` and `instability` only where they say something.
nlohmann::json to_json(const sim::StepReport& step);

} // namespace ligsim::reports
