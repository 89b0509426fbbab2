#pragma once
/// @brief `ligsim study sensitivity`: how much the knee flexion figures move when the
/// segmentation changes as a second rater or another MRI would change it (the ligament paper's
/// closing remark). One factor at a time from the source segmentation: the surface moved in and
/// out, smoothed and roughened, the attachment areas grown and shrunk, the attachment rule
/// changed, the centerline's alpha; each variant is built and swept quasi-statically. In a knee
/// every ligament is changed the same way at once (they do not touch in the sweep, so each
/// ligament's figures are its own variant's) and reported on its own.

#include "pipeline/study/study_model.hpp"
#include "sim/flexion/flexion_settings.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace ligsim::study {

struct SensitivitySettings {
  /// Surface offsets: up to one voxel of the source image (0.5 mm), in and out, and half of it.
  double offset_mm = 0.5;
  int smoothing_iterations = 10; ///< Taubin lambda/mu pairs
  double roughness_mm = 0.15;    ///< root-mean-square normal displacement of the roughening
  /// Attachment areas grown (> 0) and shrunk (< 0) along the surface, both areas at once.
  std::vector<double> attachment_changes_mm = {-2.0, -1.0, 1.0, 2.0};
  std::vector<double> alphas = {0.0, 0.5, 1.0};
  /// A changed attachment rule: the tibial area as the ligament's distal end of this length
  /// (instead of the config's rule), and the centerline between the areas' means (the paper's).
  double tibia_end_length_mm = 10.0;
  /// The factors to vary (empty: all): offset, smoothing, attachment-size, attachment-rule, alpha.
  std::vector<std::string> factors;
};

/// The factor names `SensitivitySettings::factors` accepts.
const std::vector<std::string>& sensitivity_factor_names();

struct SensitivityInputs {
  StudyModel model;
  sim::FlexionSettings flexion; ///< quasi-static; its model_dir is ignored
  SensitivitySettings settings;
  std::filesystem::path out;
  bool png = true;
};

/// Builds every variant into out/models/<name> (surfaces in out/variants/<name>, a knee's in
/// out/variants/<name>/<ligament>), sweeps it, and writes sensitivity.csv (ligament x variant x
/// angle), sensitivity.md (per ligament: figures per variant at the last angle, the spread: min /
/// median / max, and per factor the largest change and its share of the spread) and
/// sensitivity.png / .svg (largest femur force change against angle per ligament and factor).
/// Returns the figures for summary.json. A variant that fails to build or solve is reported; the
/// study fails only when the baseline does.
nlohmann::json run_sensitivity_study(const SensitivityInputs& inputs);

} // namespace ligsim::study
