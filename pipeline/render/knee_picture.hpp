#pragma once
/// @brief A PNG of a whole knee: every ligament coloured by its fiber strain on one colour scale
/// (one colour bar), its name beside it, the bones see-through around them.
///
/// Needs an X display: create an OffscreenDisplay first (pipeline/render/offscreen_display.hpp).

#include "pipeline/render/ligament_picture.hpp"

#include <filesystem>
#include <string>
#include <vector>

class vtkPolyData;
class vtkUnstructuredGrid;

namespace ligsim::render {

struct KneePicture {
  /// Deformed ligaments (points in mm) with cell data "fiber_stretch" (|F a|). Not owned.
  std::vector<vtkUnstructuredGrid*> ligaments;
  std::vector<std::string> names;  ///< one per ligament, drawn beside it
  std::vector<vtkPolyData*> bones; ///< deformed bone surfaces (mm). Not owned.
  double bone_opacity = 0.35;      ///< in (0, 1]
  std::string caption;             ///< e.g. "flexion 45 deg, front", top left
  /// The colour scale of fiber strain (stretch - 1): blue below zero (slack), white at zero, red
  /// at `strain_max`; the same for every picture of a sweep. Needs strain_min <= 0 < strain_max.
  double strain_min = -0.05;
  double strain_max = 0.1;
  int width = 1200, height = 900;
};

/// The fiber strain (|F a| - 1) at which `fraction` of the cells of all `ligaments` lie below,
/// e.g. 0.99 (a few extreme tets at a footprint's edge do not decide the scale). Throws
/// InputError if a ligament lacks "fiber_stretch" or none has a finite value.
double fiber_strain_percentile(const std::vector<vtkUnstructuredGrid*>& ligaments, double fraction);

/// Renders the picture and writes `png` atomically. Throws InputError on a missing array, an
/// empty mesh, a bad scale, camera or size, or a failed write; Error if VTK cannot render.
void render_knee_png(const KneePicture& picture, const PictureCamera& camera,
                     const std::filesystem::path& png);

} // namespace ligsim::render
