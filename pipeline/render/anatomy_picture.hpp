#pragma once
/// @brief A PNG of the knee's anatomy as the build found it: the bones see-through, each landmark
/// a coloured ball with its name, seen from the front and from the medial side, so that a user
/// can check at a glance where the epicondyles, the notch and the plateau were put.
///
/// Needs an X display: create an OffscreenDisplay first (pipeline/render/offscreen_display.hpp).

#include <Eigen/Core>

#include <filesystem>
#include <string>
#include <vector>

class vtkPolyData;

namespace ligsim::render {

struct AnatomyPicture {
  std::vector<vtkPolyData*> bones;     ///< bone surfaces (mm). Not owned.
  std::vector<vtkPolyData*> ligaments; ///< ligament surfaces (mm), drawn in grey. Not owned.
  std::vector<std::string> landmark_names;
  std::vector<Eigen::Vector3d> landmarks_mm;             ///< one per name
  Eigen::Vector3d proximal = Eigen::Vector3d::UnitY();   ///< unit: up on the screen
  Eigen::Vector3d posterior = -Eigen::Vector3d::UnitZ(); ///< unit
  Eigen::Vector3d medial = Eigen::Vector3d::UnitX();     ///< unit: the second view looks along -it
  std::string caption;
  int width = 1600, height = 900; ///< the two views side by side
};

/// Renders the picture and writes `png` atomically. Throws InputError when there is nothing to
/// draw, names and points differ in number, or the directions are not unit and across each
/// other; Error if VTK cannot render.
void render_anatomy_png(const AnatomyPicture& picture, const std::filesystem::path& png);

} // namespace ligsim::render
