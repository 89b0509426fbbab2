#pragma once
/// @brief Reads the keys of a `[contact]` table that flexion configs and scenes share.

#include "common/toml_table.hpp"
#include "sim/contact/contact_config.hpp"

namespace ligsim::sim {

/// enabled, d_hat_mm, stiffness_mpa_per_mm, voxel_mm, band_mm (default: the larger of 1 mm and
/// d_hat + 2 voxels); leaves other keys to the caller.
void read_contact_table(TomlTable& table, ContactConfig& config);

} // namespace ligsim::sim
