#include "sim/scene/contact_table.hpp"

#include <algorithm>

namespace ligsim::sim {

void read_contact_table(TomlTable& table, ContactConfig& config)
{
  if (table.has("enabled"))
    config.enabled = table.boolean("enabled", true);
  config.barrier.d_hat_mm = table.number("d_hat_mm", config.barrier.d_hat_mm);
  config.barrier.stiffness_mpa_per_mm =
      table.number("stiffness_mpa_per_mm", config.barrier.stiffness_mpa_per_mm);
  config.grid.voxel_mm = table.number("voxel_mm", config.grid.voxel_mm);
  const double least_band = config.barrier.d_hat_mm + 2.0 * config.grid.voxel_mm;
  config.grid.band_mm = table.number("band_mm", std::max(config.grid.band_mm, least_band));
}

} // namespace ligsim::sim
