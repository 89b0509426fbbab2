#pragma once
/// @brief Surfaces to a label map: the voxels whose centres lie inside each surface get its
/// label (what a segmentation would hold), for samples and tests of the label-map path.

#include "common/mesh.hpp"
#include "stages/labelmap/label_image.hpp"

#include <vector>

namespace ligsim::labelmap {

struct LabeledSurface {
  TriangleSurface surface; ///< closed
  int label = 1;
};

/// An axis-aligned label map (identity direction) over the box [lo, hi] (mm) with voxels of
/// `spacing_mm`; later surfaces overwrite earlier ones where they overlap. One ray per voxel
/// column (parity); a column whose crossings do not pair up is decided voxel by voxel.
LabelImage rasterize(const std::vector<LabeledSurface>& parts, const Eigen::Vector3d& lo,
                     const Eigen::Vector3d& hi, const Eigen::Vector3d& spacing_mm);

} // namespace ligsim::labelmap
