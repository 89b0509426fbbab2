#pragma once
/// @brief The segmentation variants of `ligsim study sensitivity` and `ligsim study variant`:
/// one factor at a time from the source (surface offset, smoothing and roughening, attachment
/// areas grown and shrunk, the attachment rule, the centerline's alpha), each a build config;
/// in a knee every ligament is changed the same way.

#include "pipeline/stage_graph/build_config.hpp"
#include "pipeline/study/sensitivity_study.hpp"
#include "pipeline/study/study_model.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace ligsim::study {

/// One variant of the model: every ligament's config changed by the same factor.
struct SensitivityVariant {
  std::string factor; ///< "baseline" for the source segmentation
  std::string name;   ///< folder name, unique
  std::string description;
  StudyModel model;
};

/// The model with the sizes that default to a fraction of a ligament's thickness (voxel h/8,
/// mesh h/2, facet distance h/20) set to its source's values, so that a thinner or thicker
/// variant is meshed as finely as the source and only its shape differs.
StudyModel pinned_sizes(const StudyModel& model);

/// The baseline (`source` itself) and the variants `settings` asks for. Each ligament's
/// attachment areas are the ones its build found in the baseline's model folder `baseline_dir`
/// (its attachments.vtp); the changed surfaces are written to
/// `folders`/<variant>/surface.vtp (in a knee `folders`/<variant>/<ligament>/surface.vtp) with
/// those areas as point-data flags.
std::vector<SensitivityVariant> make_variants(const StudyModel& source,
                                              const std::filesystem::path& baseline_dir,
                                              const SensitivitySettings& settings,
                                              const std::filesystem::path& folders);

/// One segmentation variant as files, for `ligsim build --surface FILE --femur-rule array
/// --femur-array study_femur_area --tibia-rule array --tibia-array study_tibia_area`: the
/// ligament surface of `config` changed by `kind` ("offset": moved `amount` mm along its
/// normals; "smooth": `amount` Taubin iterations; "rough": bumps of rms `amount` mm; "areas":
/// attachment areas grown (+) or shrunk (-) by `amount` mm) with the config's attachment areas
/// as point-data flags, written to `folder`/surface.vtp. Returns the file.
std::filesystem::path write_surface_variant(const pipeline::BuildConfig& config,
                                            const std::string& kind, double amount,
                                            const std::filesystem::path& folder);

} // namespace ligsim::study
