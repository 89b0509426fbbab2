#pragma once
/// @brief The knee flexion solved twice on the same settings, by ligsim and by FEBio, and the
/// two answers side by side (`ligsim verify febio`; docs/export.md).

#include "sim/febio/febio_comparison.hpp"
#include "sim/febio/febio_run.hpp"
#include "sim/febio/knee_feb.hpp"
#include "sim/flexion/knee_contact.hpp"
#include "sim/flexion/knee_flexion.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace ligsim::sim {

struct CrossCheck {
  std::vector<ComparisonRow> rows;
  std::vector<AngleResult> ours; ///< our sweep's angles
  std::vector<FebioStep> febio;  ///< FEBio's steps, measured as ours
  /// Per FEBio step, per bone: gaps and how deep FEBio's ligament goes into the bone (the
  /// independent check against the triangles; no forces).
  std::vector<std::vector<BoneContact>> febio_contact;
  std::vector<std::string> warnings;
  FebioRun run;
  double ours_wall_s = 0.0; ///< setup (body, contact grids) and sweep
  std::filesystem::path feb;
};

/// Sweeps `model` with `settings` (quasi-static) along the knee's `motion`, writes the same problem
/// to
/// `<out>/knee.feb`, runs FEBio (`febio`) on it and compares them angle by angle: femur force
/// magnitude (attachment and contact together), strain energy and mean fiber stretch. `extra_
/// wall_s` (reading the model, finding the axis) is added to our wall time. `febio_contact`:
/// the file's contact settings. Contact grids are cached in `<model_dir>/contact`. Throws
/// SolverError when either solver stops.
CrossCheck cross_check_with_febio(const KneeModel& model, const FlexionSettings& settings,
                                  const KneeMotion& motion, const std::filesystem::path& febio,
                                  const std::filesystem::path& out, double extra_wall_s = 0.0,
                                  const FebContactSettings& febio_contact = {});

} // namespace ligsim::sim
