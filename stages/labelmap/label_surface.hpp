#pragma once
/// @brief From a label map to a smooth closed surface of one label, in the image's physical
/// frame: largest 26-connected component, holes filled, discrete flying edges and windowed-sinc
/// smoothing (no staircase of the slices).

#include "common/mesh.hpp"
#include "stages/labelmap/label_image.hpp"

namespace ligsim::labelmap {

/// What the selection of a label kept and dropped.
struct Selection {
  int label = 0;
  long voxels = 0;             ///< voxels kept (largest component, holes filled)
  int components = 0;          ///< 26-connected components of the label
  long dropped_voxels = 0;     ///< in the other components
  long filled_hole_voxels = 0; ///< other voxels enclosed by the kept component
};

/// The voxels of `label` (1) as a mask in the image's index order: its largest 26-connected
/// component with the enclosed holes filled. Throws InputError if the label is absent.
std::vector<std::uint8_t> select_label(const LabelImage& image, int label, Selection* selection);

/// The smooth closed surface of `label` (see select_label), physical LPS coordinates, mm,
/// outward-facing triangles. `smoothing_iterations` of windowed-sinc smoothing (0: none), after
/// which the surface is offset along its normals to enclose the selected voxels' volume.
TriangleSurface label_surface(const LabelImage& image, int label, Selection* selection = nullptr,
                              int smoothing_iterations = 30);

} // namespace ligsim::labelmap
