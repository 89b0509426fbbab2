#pragma once
/// @brief `ligsim view`'s window: the bones and ligaments of a live knee in a VTK render window,
/// the ligaments coloured by fiber strain, the flexion angle on a slider (and the arrow keys),
/// a text overlay of the frame's figures; frames computed between renders. Played from a script
/// it draws every frame and can record them as PNG files with a frames.csv.

#include "pipeline/view/view_script.hpp"
#include "sim/flexion/knee_model.hpp"
#include "sim/flexion/live_knee.hpp"

#include <Eigen/Core>

#include <filesystem>
#include <memory>
#include <string>

namespace ligsim::cli {

struct LiveWindowOptions {
  /// A folder for frame_NNNNN.png, frames.csv and frames.pvd (with its series/); empty: none.
  std::filesystem::path record;
  int width = 1024;
  int height = 768;
  double strain_range_pct = 10.0; ///< the colour bar's top
};

/// Throws InputError, with the xvfb-run line that works, when no X display answers.
void require_display();

class LiveWindow {
public:
  /// `bones`: the knee's model (its femur moves with the knee, tibia and fibula stay);
  /// `view_axis`: the direction the camera looks along (the flexion axis: a side view).
  LiveWindow(sim::LiveKnee& knee, const sim::KneeModel& bones, const Eigen::Vector3d& view_axis,
             LiveWindowOptions options);
  ~LiveWindow();
  LiveWindow(const LiveWindow&) = delete;
  LiveWindow& operator=(const LiveWindow&) = delete;

  /// The window until the user closes it: the slider and keys move the target angle.
  void run_interactive();
  /// Plays `script` frame by frame, drawing (and recording) every frame; returns the frames.
  int run_script(const ViewScript& script);

private:
  struct Scene;
  std::unique_ptr<Scene> m_scene;
};

} // namespace ligsim::cli
