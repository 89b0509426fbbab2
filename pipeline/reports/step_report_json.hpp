#pragma once
/// @brief A load step's and an implicit Euler frame's reports as JSON: every figure under its
/// own name, once, for every writer of a step or frame (a scene's summary.json, ...).

#include "sim/solver/implicit_euler.hpp"
#include "sim/solver/static_solver.hpp"

#include <nlohmann/json.hpp>

namespace ligsim::reports {

/// The step's figures; `floor` and `instability` only where they say something.
nlohmann::json to_json(const sim::StepReport& step);
/// The frame's figures.
nlohmann::json to_json(const sim::FrameReport& frame);

} // namespace ligsim::reports
