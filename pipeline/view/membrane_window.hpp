#pragma once
/// @brief `ligsim view` of a tearing scene: the membrane in a VTK window, shaded by the tearing
/// criterion with its cracks, torn live by the scene's own pull and by a hand (the mouse's left
/// button, or a script), `frame_every` steps per drawn frame; recorded, every frame as a PNG and
/// the tear's path as tear_path.csv.

#include "pipeline/view/view_script.hpp"
#include "sim/membrane/scene/tear_simulation.hpp"

#include <filesystem>
#include <optional>

namespace ligsim::cli {

struct MembraneWindowOptions {
  std::filesystem::path record; ///< frame_NNNNN.png and tear_path.csv here; empty: none
  int width = 800;
  bool interactive = true; ///< stay open after the run until closed (else close at its end)
  /// A hand's path (columns x_mm, y_mm): it takes the sheet at the first row's point and time
  /// and lets go after the last row.
  std::optional<ViewScript> hand;
};

/// The hand: the free nodes within kHandRadiusMm (at rest) of the node picked, within
/// kHandPickMm of the pointer, follow it at most at kHandSpeedMmPerS.
constexpr double kHandRadiusMm = 1.0;
constexpr double kHandPickMm = 1.0;
constexpr double kHandSpeedMmPerS = 20.0;

/// Plays `simulation` to its end, drawing a frame every `frame_every` steps (and the last);
/// returns the frames drawn. Keys: space pauses, s takes a screenshot, q quits; the left button
/// pulls the sheet where it is pressed on it.
int play_membrane(membrane::TearSimulation& simulation, const MembraneWindowOptions& options);

} // namespace ligsim::cli
