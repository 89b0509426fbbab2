#pragma once
/// @brief A PNG of a deformed ligament coloured by strain energy density (green low, red high,
/// as the ligament paper's Figure 4), with its fibers and the bones around it.
///
/// Needs an X display: create an OffscreenDisplay first (pipeline/render/offscreen_display.hpp).

#include <Eigen/Core>

#include <filesystem>
#include <string>
#include <vector>

class vtkPolyData;
class vtkRenderer;
class vtkUnstructuredGrid;

namespace ligsim::render {

/// A parallel projection.
struct PictureCamera {
  Eigen::Vector3d focal_point_mm = Eigen::Vector3d::Zero();
  Eigen::Vector3d view_direction =
      -Eigen::Vector3d::UnitZ();                 ///< from the camera to the focal point
  Eigen::Vector3d up = Eigen::Vector3d::UnitY(); ///< up on the screen (not along view)
  double view_height_mm = 100.0;                 ///< height of the scene shown
};

/// Bone colour (RGB in [0, 1]), light ivory.
inline const Eigen::Vector3d kBoneColour(0.89, 0.85, 0.78);

struct LigamentPicture {
  /// Deformed tets (points in mm) with cell data "strain_energy_density" (MPa = mJ/mm^3) and
  /// "fiber_direction" (3 components, unit, the deformed fiber). Not owned.
  vtkUnstructuredGrid* ligament = nullptr;
  /// Deformed bone surfaces (mm), drawn in kBoneColour. Not owned.
  std::vector<vtkPolyData*> bones;
  double bone_opacity = 1.0; ///< in (0, 1]; below 1 the ligament shows through the bones
  std::string caption;       ///< e.g. "flexion 45 deg", top left
  /// Top of the colour scale (MPa), the same for every angle of a sweep; <= 0: this frame's max.
  double energy_max_mpa = 0;
  /// Ligament nodes that touch a bone (contact pressure above zero), drawn as blue dots.
  std::vector<Eigen::Vector3d> contact_points_mm;
  int max_fibers = 3000; ///< fiber strokes drawn at most (they are also kept 1.25 lengths apart)
  int width = 1200, height = 900;
};

/// Points the renderer's camera as `camera` says (parallel projection), far enough back that the
/// whole scene lies in front of it.
void place_parallel_camera(vtkRenderer* renderer, const PictureCamera& camera);

/// The strain energy density (MPa) below which `fraction` of the cells lie, e.g. 0.99: a top for
/// the colour scale that a few extreme tets (at an attachment's edge) do not decide. Throws
/// InputError if the array is missing or has no finite value.
double strain_energy_percentile_mpa(vtkUnstructuredGrid* ligament, double fraction);

/// Renders the picture and writes `png` atomically. The ligament's outer surface is coloured per
/// cell by strain energy density (clamped to red above the scale's top). Fibers are dark strokes
/// one mean tet edge long on boundary faces picked at random but evenly spaced: through the
/// face's centre, lifted a little off the surface, along its tet's fiber projected onto the face.
/// Throws InputError on a missing array, an empty mesh, a bad camera or size, or a failed write;
/// Error if VTK cannot render.
void render_ligament_png(const LigamentPicture& picture, const PictureCamera& camera,
                         const std::filesystem::path& png);

} // namespace ligsim::render
