#pragma once
/// The membrane material the unit tests share: lens-capsule-like moduli, 0.1 mm thick.

#include "sim/membrane/model/stiffness.hpp"

namespace ligsim::membrane::test {

inline MembraneMaterial lens_like_material(double density_t_per_mm3 = 1e-6)
{
  MembraneMaterial m;
  m.fiber_modulus_mpa = 6.0;
  m.transverse_modulus_mpa = 2.0;
  m.fiber_poisson = 0.45;
  m.shear_modulus_mpa = 0.7;
  m.thickness_mm = 0.1;
  m.density_t_per_mm3 = density_t_per_mm3;
  return m;
}

} // namespace ligsim::membrane::test
