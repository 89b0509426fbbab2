#pragma once
/// @brief Runs a scene: builds only what it uses (no fiber terms without fibers, no masses or
/// velocities in a quasi-static scene), solves, writes the outputs and records the figures.

#include "common/run_summary.hpp"
#include "sim/scene/scene.hpp"

#include <filesystem>
#include <string>

namespace ligsim::scenes {

struct SceneRunReport {
  bool success = false;
  std::string failure; ///< the solver's diagnostic when it stopped early
};

/// Writes step_NNNN.vtu files and series.pvd (unless disabled), reactions.csv, and fills
/// `summary` (stages "setup" and "solve", results with one entry per load step or output
/// frame: iterations, residual, energy, worst J, wall time, reaction per constraint set).
SceneRunReport run_scene(const sim::Scene& scene, const std::filesystem::path& out,
                         RunSummary& summary);

} // namespace ligsim::scenes
