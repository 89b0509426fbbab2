#pragma once
/// @brief `ligsim study sensitivity`: how much the knee flexion figures move when the
/// segmentation changes as a second rater or another MRI would change it (the ligament paper's
/// closing remark). One factor at a time from the source segmentation: the surface moved in and
/// out, smoothed and roughened, the attachment areas grown and shrunk, the attachment rule
/// changed, the centerline's alpha; each variant is built and swept quasi-statically.

#include "pipeline/stage_graph/build_config.hpp"
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
  pipeline::BuildConfig build;
  sim::FlexionSettings flexion; ///< quasi-static; its model_dir is ignored
  SensitivitySettings settings;
  std::filesystem::path out;
  bool png = true;
};

/// One segmentation variant as files, for `ligsim build --surface FILE --femur-rule array
/// --femur-array study_femur_area --tibia-rule array --tibia-array study_tibia_area`: the
/// ligament surface of `config` changed by `kind` ("offset": moved `amount` mm along its
/// normals; "smooth": `amount` Taubin iterations; "rough": bumps of rms `amount` mm; "areas":
/// attachment areas grown (+) or shrunk (-) by `amount` mm) with the config's attachment areas
/// as point-data flags, written to `folder`/surface.vtp. Returns the file.
std::filesystem::path write_surface_variant(const pipeline::BuildConfig& config,
                                            const std::string& kind, double amount,
                                            const std::filesystem::path& folder);

/// Builds every variant into out/models/<name> (surfaces in out/variants/<name>), sweeps it, and
/// writes sensitivity.csv (variant x angle), sensitivity.md (figures per variant at the last
/// angle, the spread: min / median / max, and per factor the largest change and its share of
/// the spread) and sensitivity.png / .svg (largest femur force change against angle per factor).
/// Returns the figures for summary.json. A variant that fails to build or solve is reported; the
/// study fails only when the baseline does.
nlohmann::json run_sensitivity_study(const SensitivityInputs& inputs);

} // namespace ligsim::study
