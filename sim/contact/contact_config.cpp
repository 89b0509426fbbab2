#include "sim/contact/contact_config.hpp"

#include "common/error.hpp"

#include <cmath>

namespace ligsim::sim {

void validate(const ContactConfig& config)
{
  const double d_hat = config.barrier.d_hat_mm;
  if (!(d_hat > 0.0) || !std::isfinite(d_hat))
    fail("contact: d_hat_mm must be positive, got {}", d_hat);
  if (!(config.barrier.stiffness_mpa_per_mm > 0.0) ||
      !std::isfinite(config.barrier.stiffness_mpa_per_mm))
    fail("contact: stiffness_mpa_per_mm must be positive, got {}",
         config.barrier.stiffness_mpa_per_mm);
  if (!(config.grid.voxel_mm > 0.0) || !std::isfinite(config.grid.voxel_mm))
    fail("contact: voxel_mm must be positive, got {}", config.grid.voxel_mm);
  if (!(config.grid.band_mm >= d_hat + 2.0 * config.grid.voxel_mm))
    fail("contact: band_mm ({} mm) must reach d_hat_mm plus two voxels ({} mm): the barrier "
         "needs exact distances out to d_hat",
         config.grid.band_mm, d_hat + 2.0 * config.grid.voxel_mm);
  for (const std::string& bone : config.bones)
    if (bone != "femur" && bone != "tibia" && bone != "fibula")
      fail("contact: bones are \"femur\", \"tibia\" and \"fibula\", got \"{}\"", bone);
}

} // namespace ligsim::sim
