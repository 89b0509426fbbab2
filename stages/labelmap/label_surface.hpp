#pragma once
/// @brief From a label map to a smooth closed surface of one label, in the image's physical
/// frame: largest 26-connected component, holes filled, discrete flying edges and windowed-sinc
/// smoothing (no staircase of the slices).

#include "common/mesh.hpp"
#include "stages/labelmap/label_image.hpp"

#include <string>

namespace ligsim::labelmap {

/// What the selection of a label kept and dropped.
struct Selection {
  int label = 0;
  long voxels = 0;             ///< voxels kept (largest component, holes filled)
  int components = 0;          ///< 26-connected components of the label
  long dropped_voxels = 0;     ///< in the other components
  long filled_hole_voxels = 0; ///< other voxels enclosed by the kept component
  /// How the surface was made: "smoothed" (flying edges, windowed sinc, volume restored), or
  /// "blurred" when the smoothed surface crossed itself (below).
  std::string contour = "smoothed";
  int crossing_pairs = 0; ///< triangle pairs of the smoothed surface that crossed (<= 16 counted)
};

/// The voxels of `label` (1) as a mask in the image's index order: its largest 26-connected
/// component with the enclosed holes filled. Throws InputError if the label is absent.
std::vector<std::uint8_t> select_label(const LabelImage& image, int label, Selection* selection);

/// The 26-connected pieces of `label` within its own box (see select_label: `components`, the
/// `dropped_voxels` outside the largest, the kept `voxels`). Throws InputError if it is absent.
Selection label_pieces(const LabelImage& image, int label);

/// The smooth closed surface of `label` (see select_label), physical LPS coordinates, mm,
/// outward-facing triangles. `smoothing_iterations` of windowed-sinc smoothing (0: none), after
/// which the surface is offset along its normals to enclose the selected voxels' volume.
/// Smoothing moves vertices freely, and where a part is a voxel or two thin it can carry one side
/// through the other; with `never_crossing`, such a surface is made again as the half level of the
/// mask blurred by a Gaussian (one in-plane voxel, half a slice), contoured by flying edges and
/// left as it is: a level set of one field is never crossing itself.
TriangleSurface label_surface(const LabelImage& image, int label, Selection* selection = nullptr,
                              int smoothing_iterations = 30, bool never_crossing = false);

/// The half level of `mask` blurred (the fallback above), physical coordinates, mm, outward.
TriangleSurface blurred_mask_surface(const LabelImage& image,
                                     const std::vector<std::uint8_t>& mask);

} // namespace ligsim::labelmap
