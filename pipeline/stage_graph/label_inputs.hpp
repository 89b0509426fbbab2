#pragma once
/// @brief `ligsim build --labels`: the ligament and bone surfaces taken from a segmentation
/// label map, written into the output folder, where the stages read them.

#include "pipeline/stage_graph/build_config.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>

namespace ligsim::pipeline {

/// If `config.labels` is set: reads the label map and extracts the ligament's surface (and the
/// bones' where their labels are given), checking everything before `dir` is touched; then
/// writes them into `dir` and returns the config pointing at them, with what was selected in
/// `report` (frame, spacing, components dropped, holes filled). Otherwise returns `config`.
BuildConfig surfaces_from_labels(const BuildConfig& config, const std::filesystem::path& dir,
                                 nlohmann::json& report);

/// A label given as text: a number (a name resolves through the map's segment names when
/// those are read; today only numbers).
int parse_label(const std::string& text, const std::string& what);

} // namespace ligsim::pipeline
