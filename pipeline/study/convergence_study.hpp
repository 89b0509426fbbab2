#pragma once
/// @brief `ligsim study convergence`: error against run time on the knee flexion of a built
/// model. Ladders of mesh sizes and voxel sizes (quasi-static) and of time steps (interactive);
/// every run is compared with the finest quasi-static run (and, where the three finest meshes
/// converge monotonically, with the Richardson extrapolation). A knee's ligaments are each
/// scaled from their own sizes, swept together and compared each with its own reference.

#include "pipeline/stage_graph/build_config.hpp"
#include "pipeline/study/study_model.hpp"
#include "sim/flexion/flexion_settings.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <vector>

namespace ligsim::study {

/// Sizes are factors of the build config's: its cell and facet sizes and facet distance, its
/// voxel spacing, or where it leaves them at 0 the build's defaults h/2, h/20 and h/8 (h = 2
/// volume / area of the ligament; each ligament of a knee its own).
struct ConvergenceLadder {
  std::vector<double> mesh_scales = {3.0, 2.2, 1.6, 1.25, 1.0, 0.8, 0.63, 0.5};
  std::vector<double> voxel_scales = {2.0, 1.4, 1.0, 0.7, 0.5};
  double voxel_mesh_scale = 1.0; ///< the mesh the voxel ladder uses
  std::vector<double> time_steps_s = {0.03, 0.01, 0.003, 0.001};
  /// The meshes the interactive runs use.
  std::vector<double> interactive_mesh_scales = {1.6, 1.25, 1.0};
  /// The element orders of the mesh ladder, each a family of its own (1: linear tets, 2: 10-node
  /// tets); the finest mesh of the highest is the reference, and the voxel and interactive runs
  /// take the lowest. Empty: the config's own order, one family.
  std::vector<int> orders;
};

struct ConvergenceInputs {
  StudyModel model;
  sim::FlexionSettings flexion; ///< its model_dir is ignored: each run builds its own
  ConvergenceLadder ladder;
  std::filesystem::path out;
  bool png = true; ///< the plot as PNG too (needs an X display: render::OffscreenDisplay)
};

/// Runs the ladders into `out` (models in out/models/<name>, reused when current) and writes
/// convergence.csv (one row per ligament and run), convergence_angles.csv (one row per ligament,
/// run and angle), convergence.md and convergence.png / .svg (worst energy error against solve
/// time per frame, log-log, one curve per family and ligament, the paper's 15 frames per second
/// marked), and names per ligament the quasi-static run that comes within 1 % of the reference's
/// femur force at every angle in the least solve time. Returns the figures for summary.json. A run
/// that fails is reported as such; the study fails only when a ligament's reference run does.
nlohmann::json run_convergence_study(const ConvergenceInputs& inputs);

/// 2 volume / area of the ligament surface (mm): the thickness the build's defaults scale with
/// (the same formula as the voxelize and tetmesh stages).
double ligament_thickness_mm(const pipeline::BuildConfig& config);

} // namespace ligsim::study
