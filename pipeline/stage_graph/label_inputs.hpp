#pragma once
/// @brief `ligsim build --labels`: the ligament and bone surfaces taken from a segmentation
/// label map, written into the output folder, where the stages read them.

#include "pipeline/stage_graph/build_config.hpp"
#include "pipeline/stage_graph/knee_config.hpp"
#include "stages/labelmap/label_image.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace ligsim::pipeline {

/// The share of a ligament's voxels that may lie outside its largest 26-connected piece, dropped
/// as stray voxels. More, and the ligament fell apart (a band thinner than the map's voxels breaks
/// between them): the build refuses it.
inline constexpr double ligament_stray_share = 0.05;

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

/// The names of the map's labels: its segment names, then those of its colour table
/// (`colour_table`, else labelmap::colour_tables_found); the tables read go to `tables`.
std::vector<labelmap::LabelName> label_names(const std::filesystem::path& labels,
                                             const std::filesystem::path& colour_table,
                                             const labelmap::LabelImage& image,
                                             std::vector<std::filesystem::path>& tables);

/// One surface to take from a label map.
struct LabelPart {
  std::string name;           ///< what it is, in messages and the report ("femur", "ligament ACL")
  std::string label;          ///< a number or a name, as text
  bool bone = false;          ///< repaired into one closed shell (repair::repair_bone)
  std::filesystem::path file; ///< where its surface goes (.vtp)
};

/// Extracts every part's surface from the label map `labels` (names resolved through its segment
/// names and `colour_table`, or every table beside the map when empty), checking all of them
/// before writing any; then writes each to its file. Returns the report: the map's frame and,
/// per part name, what was selected (and a bone's shells and repair).
nlohmann::json write_label_surfaces(const std::filesystem::path& labels,
                                    const std::filesystem::path& colour_table,
                                    const std::vector<LabelPart>& parts);

/// If `knee.labels` is set: takes the bones (labels_femur.vtp, labels_tibia.vtp,
/// labels_fibula.vtp in `dir`) and every ligament (labels_ligament.vtp in its folder) from the
/// label map, checking all before writing any, and returns the knee pointing at them, with what
/// was selected in `report`. Otherwise returns `knee`.
KneeConfig knee_surfaces_from_labels(const KneeConfig& knee, const std::filesystem::path& dir,
                                     nlohmann::json& report);

} // namespace ligsim::pipeline
