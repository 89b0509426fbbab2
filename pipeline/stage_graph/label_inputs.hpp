#pragma once
/// @brief `ligsim build --labels`: the ligament and bone surfaces taken from a segmentation
/// label map, written into the output folder, where the stages read them.

#include "pipeline/stage_graph/build_config.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>

namespace ligsim::pipeline {

/// The ligament's surface from a label map, in the output folder (the bones' are femur.vtp and
/// tibia.vtp, which the model stage then keeps as they are).
inline constexpr const char* ligament_from_labels = "labels_ligament.vtp";

/// If `config.labels` is set: reads the label map, resolves the labels (numbers or names: the
/// map's segment names and its colour table, `config.colour_table` or one beside the map) and
/// extracts the ligament's surface (and the bones' where their labels are given), checking
/// everything before `dir` is touched; then writes them into `dir` (ligament_from_labels,
/// femur.vtp, tibia.vtp) and returns the config pointing at them, with what was selected in
/// `report` (frame, spacing, label names, components dropped, holes filled; for a bone, the
/// shells its surface had and the repair that left one: repair::repair_bone). Otherwise returns
/// `config`.
BuildConfig surfaces_from_labels(const BuildConfig& config, const std::filesystem::path& dir,
                                 nlohmann::json& report);

} // namespace ligsim::pipeline
