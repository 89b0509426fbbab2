#pragma once
/// @brief Segmentation label maps (NRRD, NIfTI, MetaImage) in their physical frame, through ITK
/// (label_image.cpp is the one translation unit that includes it).

#include "stages/labelmap/label_names.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <filesystem>
#include <vector>

namespace ligsim::labelmap {

/// A 3-D image of integer labels, with the geometry ITK reads: voxel (i, j, k) has its centre at
/// origin + direction * diag(spacing) * (i, j, k), in the physical LPS frame, mm. Labels are
/// stored x-fastest.
struct LabelImage {
  Eigen::Vector3i dims = Eigen::Vector3i::Zero();
  Eigen::Vector3d spacing_mm = Eigen::Vector3d::Ones();
  Eigen::Vector3d origin_mm = Eigen::Vector3d::Zero();
  Eigen::Matrix3d direction = Eigen::Matrix3d::Identity(); ///< columns: the index axes
  std::vector<std::int32_t> labels;
  /// Slicer's segment names from a NRRD header (`SegmentN_Name`, `SegmentN_LabelValue`).
  std::vector<LabelName> segment_names;
  /// Made from surfaces (`ligsim labelmap`): its frame is theirs, not a scanner's, and says
  /// nothing of the anatomy (NRRD key `ligsim_frame:=surfaces`; other formats cannot carry it).
  bool frame_from_surfaces = false;

  std::size_t index(int i, int j, int k) const
  {
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(dims.x()) * (j + static_cast<std::size_t>(dims.y()) * k);
  }
  std::int32_t& operator()(int i, int j, int k) { return labels[index(i, j, k)]; }
  std::int32_t operator()(int i, int j, int k) const { return labels[index(i, j, k)]; }
  /// Physical point of continuous index coordinates, mm.
  Eigen::Vector3d physical_point(const Eigen::Vector3d& ijk) const
  {
    return origin_mm + direction * spacing_mm.asDiagonal() * ijk;
  }
};

/// Reads `.nrrd` (and `.seg.nrrd` with one 3-D layer), `.nii`, `.nii.gz`, `.mha`, `.mhd`.
/// Throws InputError naming the file if it is missing, unreadable, not 3-D (a 4-D layered
/// segmentation included) or not of integer labels.
LabelImage read_label_image(const std::filesystem::path& file);

/// Writes the image in the format its extension names (the list above), atomically; a NRRD
/// file carries the segment names as Slicer's segment keys.
void write_label_image(const LabelImage& image, const std::filesystem::path& file);

} // namespace ligsim::labelmap
