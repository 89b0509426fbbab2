#pragma once
/// @brief How far a flexion run is from a reference: per angle, the relative errors of strain
/// energy, mean and 95th-percentile fiber strain and femur force; and the Richardson
/// extrapolation of a mesh ladder where it converges monotonically.

#include "pipeline/study/study_runs.hpp"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace ligsim::study {

/// The quantities compared, in the order of the tables' columns. The regional peak is the largest
/// fiber strain over 2 mm regions (sim/flexion/regional_strain.hpp), the peak the docs judge.
enum class Quantity { energy, mean_strain, p95_strain, femur_force, regional_strain };
inline constexpr std::array<Quantity, 5> kQuantities = {Quantity::energy, Quantity::mean_strain,
                                                        Quantity::p95_strain, Quantity::femur_force,
                                                        Quantity::regional_strain};
/// One figure per quantity, by Quantity.
using QuantityValues = std::array<double, kQuantities.size()>;
std::string to_string(Quantity quantity);

/// Relative errors (fractions) at one angle. Fiber figures compare strains (stretch - 1), since
/// a stretch of 1.03 against 1.02 is a 50 % error of the strain but 1 % of the stretch; the
/// force compares vectors: |F - F_ref| / |F_ref|.
struct AngleErrors {
  double angle_deg = 0.0;
  QuantityValues error{}; ///< by Quantity
};

/// The errors of `run` against `reference` at the angles both reached (matched by angle).
std::vector<AngleErrors> angle_errors(const FlexionFigures& run, const FlexionFigures& reference);

/// The largest error over the angles, by Quantity (NaN where no angle is shared or has it).
QuantityValues worst_errors(const std::vector<AngleErrors>& errors);

/// Richardson extrapolation from three runs at mesh sizes h1 > h2 > h3 (values f1, f2, f3):
/// f = f_inf + C h^p. Returns f_inf and p when the differences keep their sign and shrink
/// (monotone convergence, 0.5 <= p <= 6); nothing otherwise.
struct Extrapolation {
  double value = 0.0;
  double order = 0.0;
};
std::optional<Extrapolation> richardson(const std::array<double, 3>& h,
                                        const std::array<double, 3>& f);

/// The scalar a quantity is compared by (energy in mJ, strains, force magnitude in N).
double quantity_value(const AngleFigures& angle, Quantity quantity);

} // namespace ligsim::study
