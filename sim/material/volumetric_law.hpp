#pragma once
/// @brief The volumetric penalty F_V(J) (eq. 22) and the ln J variant, with two derivatives.

#include "sim/material/material_parameters.hpp"

#include <cmath>

namespace ligsim::sim {

struct VolumetricResponse {
  double energy = 0.0; ///< F_V, MPa
  double d1 = 0.0;     ///< dF_V/dJ
  double d2 = 0.0;     ///< d^2F_V/dJ^2
};

/// F_V at J > 0 (callers reject inverted elements first).
inline VolumetricResponse volumetric_response(VolumetricLaw law, double k_mpa, double J)
{
  VolumetricResponse response;
  if (law == VolumetricLaw::jm1) {
    response.energy = 0.5 * k_mpa * (J - 1.0) * (J - 1.0);
    response.d1 = k_mpa * (J - 1.0);
    response.d2 = k_mpa;
  } else {
    const double log_j = std::log(J);
    response.energy = 0.5 * k_mpa * log_j * log_j;
    response.d1 = k_mpa * log_j / J;
    response.d2 = k_mpa * (1.0 - log_j) / (J * J);
  }
  return response;
}

} // namespace ligsim::sim
