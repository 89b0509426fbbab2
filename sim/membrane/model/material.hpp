#pragma once
/// @brief Parameters of a transversely isotropic membrane (Allard et al., section 2.1).

#include <string>

namespace ligsim::membrane {

/// Units: mm, N, s, tonne, so stresses are MPa and densities t/mm^3.
struct MembraneMaterial {
  double fiber_modulus_mpa = 0.0;      ///< E_F, along the fibers
  double transverse_modulus_mpa = 0.0; ///< E_T, across the fibers
  /// nu_F: transverse contraction under a stress along the fibers. The other Poisson
  /// ratio follows from symmetry: nu_T / E_T = nu_F / E_F.
  double fiber_poisson = 0.0;
  double shear_modulus_mpa = 0.0; ///< G_F, in-plane shear
  double thickness_mm = 0.0;
  double density_t_per_mm3 = 0.0;

  /// nu_T = nu_F E_T / E_F.
  double transverse_poisson() const
  {
    return fiber_poisson * transverse_modulus_mpa / fiber_modulus_mpa;
  }
};

/// Throws InputError naming `where` if the stiffness would not be positive definite
/// (a modulus <= 0, nu_F^2 E_T / E_F >= 1) or thickness / density are not positive.
void validate(const MembraneMaterial& material, const std::string& where);

} // namespace ligsim::membrane
