#pragma once
/// @brief The FEBio problem of a knee flexion sweep: the same model, material, in-situ strain,
/// femur motion and contact as `ligsim flexion` on `settings` (docs/export.md).

#include "sim/febio/feb_problem.hpp"
#include "sim/flexion/flexion_settings.hpp"
#include "sim/flexion/knee_flexion.hpp"
#include "sim/flexion/knee_model.hpp"
#include "sim/solver/boundary_conditions.hpp"

#include <string>
#include <vector>

namespace ligsim::sim {

/// Bones in the file's order: the femur (index 0), the tibia (index 1), the fibula where the
/// model has one (index 2).
constexpr std::size_t feb_femur = 0;
constexpr std::size_t feb_tibia = 1;
constexpr std::size_t feb_fibula = 2; ///< where the model has one

/// `model` as a .feb file holds it: where the config reshapes the overlap with the bones
/// (ContactConfig::reshape_overlap, contact on), the ligament pushed out of them as `ligsim
/// flexion` pushes it (with_overlap_reshaped; the bones' distance grids cached in
/// settings.model_dir/contact); `model` itself otherwise. `report` (if given) says what the push
/// did.
KneeModel feb_start_model(const KneeModel& model, const FlexionSettings& settings,
                          const BoundaryConditions& conditions, OverlapReport* report = nullptr);

/// The problem of sweeping `model` through `steps` with the femur's motion of `conditions`
/// (knee_conditions): one step per angle, the femur's rotations taken about `center_mm` (a
/// point of the flexion axis), the tibia and fibula fixed, the distal footprint bound to
/// model.distal_bone, contact with the bones settings.contact names
/// when it is on. FEBio implements only the `weiss` fiber convention: a `paper` material is
/// written with FEBio's law and the same constants, and a warning among the notes says so
/// (`warnings` receives it too). `contact`: FEBio's contact settings (penalty scale).
FebProblem knee_feb_problem(const KneeModel& model, const FlexionSettings& settings,
                            const BoundaryConditions& conditions, const SweepSteps& steps,
                            const Eigen::Vector3d& center_mm, std::vector<std::string>& warnings,
                            const FebContactSettings& contact = {});

} // namespace ligsim::sim
