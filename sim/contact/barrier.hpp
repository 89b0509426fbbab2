#pragma once
/// @brief The IPC barrier of Li et al. 2020, b(d) = -(d - d_hat)^2 ln(d / d_hat) for
/// 0 < d < d_hat, 0 beyond, +infinity at and below 0: C2 at d_hat, unbounded at contact.

#include <cmath>

namespace ligsim::sim {

struct BarrierValue {
  double value = 0.0;  ///< mm^2
  double first = 0.0;  ///< db/dd, mm
  double second = 0.0; ///< d2b/dd2, dimensionless
};

inline BarrierValue ipc_barrier(double d, double d_hat)
{
  BarrierValue b;
  if (d >= d_hat)
    return b;
  if (!(d > 0.0)) {
    b.value = INFINITY;
    return b;
  }
  const double gap = d - d_hat;
  const double log_ratio = std::log(d / d_hat);
  b.value = -gap * gap * log_ratio;
  b.first = -2.0 * gap * log_ratio - gap * gap / d;
  b.second = -2.0 * log_ratio - 4.0 * gap / d + gap * gap / (d * d);
  return b;
}

} // namespace ligsim::sim
