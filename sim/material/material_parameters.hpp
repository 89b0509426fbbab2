#pragma once
/// @brief Parameters of the transversely isotropic hyperelastic law (Weiss 1996, ligament paper
/// sec. 2.2 and 4.2): Neo-Hookean ground substance, an optional collagen fiber family and a
/// volumetric penalty. Units: mm, N, MPa.

#include <optional>
#include <string>

namespace ligsim::sim {

/// What the three fiber expressions of eq. 14 mean.
enum class FiberConvention {
  /// The paper's eq. 14: the expressions give dF_C/dlambda.
  paper,
  /// Weiss 1996 as FEBio implements it (FEUncoupledFiberExpLinear): the expressions give
  /// lambda dF_C/dlambda.
  weiss,
};

/// The volumetric penalty F_V(J).
enum class VolumetricLaw {
  /// K/2 (J - 1)^2: the paper's eq. 22, FEBio's "Abaqus" pressure model.
  jm1,
  /// K/2 (ln J)^2: FEBio's default for uncoupled materials.
  lnj,
};

/// The collagen fiber law F_C(lambda), eq. 14 / 18.
struct FiberParameters {
  double c3_mpa = 2.07;      ///< toe scale
  double c4 = 61.44;         ///< toe exponent (dimensionless)
  double c5_mpa = 640.7;     ///< linear-region modulus
  double lambda_star = 1.03; ///< stretch where the toe region ends
  FiberConvention convention = FiberConvention::paper;
};

struct MaterialParameters {
  double mu_mpa = 27.7;             ///< shear modulus of the ground substance
  double bulk_modulus_mpa = 1000.0; ///< K of the volumetric penalty
  VolumetricLaw volumetric = VolumetricLaw::jm1;
  /// Absent: pure Neo-Hookean, no fiber term is computed anywhere.
  std::optional<FiberParameters> fiber;
};

/// The MCL parameters of the paper's sec. 4.2 (paper convention, jm1 penalty, with fibers).
MaterialParameters mcl_material();

/// Throws InputError naming the first parameter that is not finite and positive
/// (lambda_star must exceed 1).
void validate(const MaterialParameters& parameters);

/// "paper" / "weiss"; throws InputError naming `where` otherwise.
FiberConvention parse_fiber_convention(const std::string& text, const std::string& where);
/// "jm1" / "lnj"; throws InputError naming `where` otherwise.
VolumetricLaw parse_volumetric_law(const std::string& text, const std::string& where);

std::string to_string(FiberConvention convention);
std::string to_string(VolumetricLaw law);

} // namespace ligsim::sim
