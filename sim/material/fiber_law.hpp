#pragma once
/// @brief The collagen fiber law F_C(lambda) of eq. 14 / 18, in both conventions, with its
/// energy (needed by line searches and finite-difference checks) and two derivatives.

#include "sim/material/material_parameters.hpp"

namespace ligsim::sim {

/// F_C and its derivatives at one deviatoric fiber stretch lambda (MPa).
struct FiberResponse {
  double energy = 0.0; ///< F_C(lambda), zero at lambda <= 1
  double d1 = 0.0;     ///< dF_C/dlambda
  double d2 = 0.0;     ///< d^2F_C/dlambda^2
};

enum class FiberRegime { slack, toe, linear };

class FiberLaw {
public:
  explicit FiberLaw(const FiberParameters& parameters);

  FiberRegime regime(double lambda) const;
  FiberResponse evaluate(double lambda) const;

  /// C6 of eq. 14, chosen so that the toe and linear expressions meet at lambda*.
  double c6_mpa() const { return m_c6; }
  const FiberParameters& parameters() const { return m_parameters; }

private:
  /// The expression g of eq. 14 and its derivative: g = C3 (exp(C4 (lambda - 1)) - 1) in the
  /// toe, C5 lambda + C6 above lambda*.
  double g(double lambda) const;
  double g_prime(double lambda) const;
  /// F_C(lambda) for 1 <= lambda <= lambda*.
  double toe_energy(double lambda) const;

  FiberParameters m_parameters;
  double m_c6 = 0.0;
  double m_energy_at_star = 0.0;
};

} // namespace ligsim::sim
