#pragma once
/// @brief `ligsim view` of a tearing scene: the membrane in a VTK window, shaded by the tearing
/// criterion with its cracks, torn live by the scene's own pull, `frame_every` steps per drawn
/// frame; recorded, every frame as a PNG and the tear's path as tear_path.csv.

#include "sim/membrane/scene/tear_simulation.hpp"

#include <filesystem>

namespace ligsim::cli {

struct MembraneWindowOptions {
  std::filesystem::path record; ///< frame_NNNNN.png and tear_path.csv here; empty: none
  int width = 800;
  bool interactive = true; ///< stay open after the run until closed (else close at its end)
};

/// Plays `simulation` to its end, drawing a frame every `frame_every` steps (and the last);
/// returns the frames drawn. Keys: space pauses, s takes a screenshot, q quits.
int play_membrane(membrane::TearSimulation& simulation, const MembraneWindowOptions& options);

} // namespace ligsim::cli
