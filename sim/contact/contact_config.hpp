#pragma once
/// @brief What a `[contact]` table of a flexion config or a scene sets: whether contact is on,
/// the barrier's activation distance and stiffness, the bones' grids, which bones.

#include "sim/contact/bone_level_set.hpp"
#include "sim/contact/contact_potential.hpp"

#include <optional>
#include <string>
#include <vector>

namespace ligsim::sim {

struct ContactConfig {
  std::optional<bool> enabled; ///< unset: on where the model has bone surfaces
  ContactSettings barrier;
  LevelSetSettings grid;
  /// flexion: which bones ("femur", "tibia", "fibula"); empty: every bone the model has
  std::vector<std::string> bones;
  /// flexion: the push of the ligament out of the bones it overlaps as segmented corrects its
  /// shape (the pushed shape, found without the in-situ strain, is the stress-free rest shape:
  /// a segmentation's overlap is an error of its shape, not a strain of the tissue) instead of
  /// deforming it (false: its strain stays in every answer).
  bool reshape_overlap = true;
};

/// Throws InputError naming the first value that cannot work (d_hat, stiffness, voxel, band
/// narrower than d_hat plus two voxels).
void validate(const ContactConfig& config);

} // namespace ligsim::sim
