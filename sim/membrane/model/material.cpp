#include "sim/membrane/model/material.hpp"

#include "common/error.hpp"

#include <cmath>

namespace ligsim::membrane {

void validate(const MembraneMaterial& m, const std::string& where)
{
  const auto positive = [&](double value, const char* name) {
    if (!(value > 0.0) || !std::isfinite(value))
      fail("{}: {} must be a positive number, got {}", where, name, value);
  };
  positive(m.fiber_modulus_mpa, "fiber_modulus_mpa");
  positive(m.transverse_modulus_mpa, "transverse_modulus_mpa");
  positive(m.shear_modulus_mpa, "shear_modulus_mpa");
  positive(m.thickness_mm, "thickness_mm");
  positive(m.density_t_per_mm3, "density_t_per_mm3");
  if (!std::isfinite(m.fiber_poisson) || m.fiber_poisson * m.transverse_poisson() >= 1.0)
    fail("{}: fiber_poisson {} gives nu_F * nu_T >= 1 (E_F {} MPa, E_T {} MPa): the stiffness "
         "would not be positive definite",
         where, m.fiber_poisson, m.fiber_modulus_mpa, m.transverse_modulus_mpa);
}

} // namespace ligsim::membrane
