#include "pipeline/study/run_errors.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ligsim::study {

std::string to_string(Quantity quantity)
{
  switch (quantity) {
  case Quantity::energy:
    return "strain_energy";
  case Quantity::mean_strain:
    return "mean_fiber_strain";
  case Quantity::p95_strain:
    return "p95_fiber_strain";
  case Quantity::femur_force:
    return "femur_force";
  case Quantity::regional_strain:
    return "regional_peak_fiber_strain";
  }
  return "?";
}

double quantity_value(const AngleFigures& angle, Quantity quantity)
{
  switch (quantity) {
  case Quantity::energy:
    return angle.strain_energy_mj;
  case Quantity::mean_strain:
    return angle.mean_fiber_stretch - 1.0;
  case Quantity::p95_strain:
    return angle.p95_fiber_stretch - 1.0;
  case Quantity::femur_force:
    return angle.femur_force_n.norm();
  case Quantity::regional_strain:
    return angle.regional_fiber_stretch - 1.0;
  }
  return 0.0;
}

std::vector<AngleErrors> angle_errors(const FlexionFigures& run, const FlexionFigures& reference)
{
  std::vector<AngleErrors> errors;
  for (const AngleFigures& a : run.angles) {
    const auto match =
        std::find_if(reference.angles.begin(), reference.angles.end(), [&](const AngleFigures& r) {
          return std::abs(r.angle_deg - a.angle_deg) < 1e-9;
        });
    if (match == reference.angles.end())
      continue;
    AngleErrors row;
    row.angle_deg = a.angle_deg;
    for (std::size_t q = 0; q < kQuantities.size(); ++q) {
      const Quantity quantity = kQuantities[q];
      if (quantity == Quantity::femur_force)
        row.error[q] = (a.femur_force_n - match->femur_force_n).norm() /
                       std::max(match->femur_force_n.norm(), 1e-300);
      else
        row.error[q] = std::abs(quantity_value(a, quantity) - quantity_value(*match, quantity)) /
                       std::max(std::abs(quantity_value(*match, quantity)), 1e-300);
    }
    errors.push_back(row);
  }
  return errors;
}

QuantityValues worst_errors(const std::vector<AngleErrors>& errors)
{
  // NaN where no angle has the figure (a run whose figures lack it), not zero.
  QuantityValues worst;
  worst.fill(std::numeric_limits<double>::quiet_NaN());
  for (const AngleErrors& row : errors)
    for (std::size_t q = 0; q < worst.size(); ++q)
      if (std::isfinite(row.error[q]))
        worst[q] = std::isnan(worst[q]) ? row.error[q] : std::max(worst[q], row.error[q]);
  return worst;
}

std::optional<Extrapolation> richardson(const std::array<double, 3>& h,
                                        const std::array<double, 3>& f)
{
  const double d12 = f[1] - f[0];
  const double d23 = f[2] - f[1];
  if (!(h[0] > h[1] && h[1] > h[2] && h[2] > 0.0) || d12 == 0.0 || d23 == 0.0 ||
      (d12 > 0) != (d23 > 0) || std::abs(d23) >= std::abs(d12))
    return std::nullopt;
  // d12 / d23 = (h1^p - h2^p) / (h2^p - h3^p): the right side grows with p for h1 > h2 > h3,
  // so bisection on p finds the order.
  const double target = d12 / d23;
  auto ratio = [&](double p) {
    return (std::pow(h[0], p) - std::pow(h[1], p)) / (std::pow(h[1], p) - std::pow(h[2], p));
  };
  double low = 0.5, high = 6.0;
  if (target < ratio(low) || target > ratio(high))
    return std::nullopt;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (low + high);
    (ratio(mid) < target ? low : high) = mid;
  }
  const double p = 0.5 * (low + high);
  const double c = d23 / (std::pow(h[2], p) - std::pow(h[1], p));
  return Extrapolation{f[2] - c * std::pow(h[2], p), p};
}

} // namespace ligsim::study
