#include "sim/material/fiber_law.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace ligsim::sim {

namespace {

// 8-point Gauss-Legendre rule on [-1, 1].
constexpr std::array<double, 4> gauss_nodes = {0.1834346424956498, 0.5255324099163290,
                                               0.7966664774136267, 0.9602898564975363};
constexpr std::array<double, 4> gauss_weights = {0.3626837833783620, 0.3137066458778873,
                                                 0.2223810344533745, 0.1012285362903763};

} // namespace

FiberLaw::FiberLaw(const FiberParameters& parameters)
    : m_parameters(parameters)
{
  const double star = parameters.lambda_star;
  m_c6 = parameters.c3_mpa * std::expm1(parameters.c4 * (star - 1.0)) - parameters.c5_mpa * star;
  m_energy_at_star = toe_energy(star);
}

FiberRegime FiberLaw::regime(double lambda) const
{
  if (lambda < 1.0)
    return FiberRegime::slack;
  return lambda < m_parameters.lambda_star ? FiberRegime::toe : FiberRegime::linear;
}

double FiberLaw::g(double lambda) const
{
  if (lambda < m_parameters.lambda_star)
    return m_parameters.c3_mpa * std::expm1(m_parameters.c4 * (lambda - 1.0));
  return m_parameters.c5_mpa * lambda + m_c6;
}

double FiberLaw::g_prime(double lambda) const
{
  if (lambda < m_parameters.lambda_star)
    return m_parameters.c3_mpa * m_parameters.c4 * std::exp(m_parameters.c4 * (lambda - 1.0));
  return m_parameters.c5_mpa;
}

double FiberLaw::toe_energy(double lambda) const
{
  const double c3 = m_parameters.c3_mpa;
  const double c4 = m_parameters.c4;
  const double x = lambda - 1.0;
  if (m_parameters.convention == FiberConvention::paper)
    return c3 * (std::expm1(c4 * x) / c4 - x);
  // Weiss: F_C = integral from 1 to lambda of g(s)/s ds, which has no elementary closed form.
  // Composite Gauss-Legendre with panels spanning at most 1 in the exponent is exact to
  // round-off for this smooth integrand.
  const int panels = std::max(1, static_cast<int>(std::ceil(c4 * x)));
  const double width = x / panels;
  double sum = 0.0;
  for (int p = 0; p < panels; ++p) {
    const double middle = 1.0 + (p + 0.5) * width;
    for (std::size_t k = 0; k < gauss_nodes.size(); ++k) {
      for (double side : {-1.0, 1.0}) {
        const double s = middle + side * gauss_nodes[k] * 0.5 * width;
        sum += gauss_weights[k] * std::expm1(c4 * (s - 1.0)) / s;
      }
    }
  }
  return c3 * sum * 0.5 * width;
}

FiberResponse FiberLaw::evaluate(double lambda) const
{
  FiberResponse response;
  switch (regime(lambda)) {
  case FiberRegime::slack:
    return response;
  case FiberRegime::toe:
    response.energy = toe_energy(lambda);
    break;
  case FiberRegime::linear: {
    const double star = m_parameters.lambda_star;
    const double c5 = m_parameters.c5_mpa;
    if (m_parameters.convention == FiberConvention::paper)
      response.energy =
          m_energy_at_star + 0.5 * c5 * (lambda * lambda - star * star) + m_c6 * (lambda - star);
    else
      response.energy = m_energy_at_star + c5 * (lambda - star) + m_c6 * std::log(lambda / star);
    break;
  }
  }
  const double value = g(lambda);
  const double slope = g_prime(lambda);
  if (m_parameters.convention == FiberConvention::paper) {
    response.d1 = value;
    response.d2 = slope;
  } else {
    response.d1 = value / lambda;
    response.d2 = slope / lambda - value / (lambda * lambda);
  }
  return response;
}

} // namespace ligsim::sim
