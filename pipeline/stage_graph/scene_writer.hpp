#pragma once
/// @brief The scene file the model stage writes beside model.vtu, for `ligsim simulate`.

#include "pipeline/stage_graph/build_config.hpp"
#include "stages/model/model.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace ligsim::pipeline {

/// A knee flexion sweep of the built model: tibia nodes fixed, femur nodes rotated about
/// `axis` from 0 to the configured angle, the material of the config, quasi-static.
/// `bones` lists the bone surface files written beside it (for the scene's pictures).
void write_scene(const std::filesystem::path& file, const BuildConfig& config,
                 const model::Axis& axis, const std::vector<std::string>& bones);

} // namespace ligsim::pipeline
