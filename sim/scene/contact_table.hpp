#pragma once
/// @brief The keys of a `[contact]` table that flexion configs and scenes share, and their reader.

#include "common/toml_table.hpp"
#include "sim/contact/contact_config.hpp"

namespace ligsim::sim {

/// The shared keys of [contact]: enabled, d_hat_mm, stiffness_mpa_per_mm, voxel_mm, band_mm.
/// visit(key, member) for each; `c` may be const (writing) or not (reading).
template <class C, class Visit> void visit_contact(C& c, Visit&& visit)
{
  visit("enabled", c.enabled);
  visit("d_hat_mm", c.barrier.d_hat_mm);
  visit("stiffness_mpa_per_mm", c.barrier.stiffness_mpa_per_mm);
  visit("voxel_mm", c.grid.voxel_mm);
  visit("band_mm", c.grid.band_mm);
}

/// band_mm where the config gives none: the larger of its value and d_hat + 2 voxels.
void widen_band_to_barrier(ContactConfig& config);

/// Reads the keys of visit_contact over `config` (band_mm widened where not given); leaves other
/// keys to the caller.
void read_contact_table(TomlTable& table, ContactConfig& config);

} // namespace ligsim::sim
