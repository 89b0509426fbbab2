#pragma once
/// @brief The companion model beside a built model: the same ligament meshed coarser, from the
/// same voxels, centerline and field, for `ligsim flexion`'s estimate of its discretisation
/// error (sim/flexion/error_estimate.hpp).

#include "pipeline/stage_graph/build_config.hpp"

#include <filesystem>

namespace ligsim {
class RunSummary;
}

namespace ligsim::pipeline {

/// Builds the companion of the model in `dir` into dir/companion (common/knee_manifest.hpp):
/// the tetmesh, fibers and model stages rerun with the sizes the tetmesh stage used, scaled until
/// the companion's elements are config.error_estimate.mesh_scale times the model's in size; the
/// stages before them are linked from `dir`, not rerun.
/// The stages it reruns go into `summary` as "companion/<stage>". With a scale of 0 an old
/// companion is removed. A companion that cannot be built (a mesh too coarse for the surface) is
/// removed and said on stderr and in the summary: the model stands, and its flexion reports no
/// estimate.
void build_companion(const BuildConfig& config, const std::filesystem::path& dir, bool force,
                     RunSummary& summary);

} // namespace ligsim::pipeline
