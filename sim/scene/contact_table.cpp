#include "sim/scene/contact_table.hpp"

#include "common/config_section.hpp"

#include <algorithm>

namespace ligsim::sim {

void widen_band_to_barrier(ContactConfig& config)
{
  config.grid.band_mm =
      std::max(config.grid.band_mm, config.barrier.d_hat_mm + 2.0 * config.grid.voxel_mm);
}

void read_contact_table(TomlTable& table, ContactConfig& config)
{
  ConfigSection section(table);
  visit_contact(config, FieldReader{section});
  if (!table.has("band_mm"))
    widen_band_to_barrier(config);
}

} // namespace ligsim::sim
