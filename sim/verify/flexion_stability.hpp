#pragma once
/// @brief `verify stability --suite flexion`: the extreme cases of the real job on a built knee
/// model. Flexion to 140 degrees, in-situ strain 0 to 10 %, K from 1e2 to 1e6 MPa, C5 times 10,
/// a coarse and a fine model, interactive time steps from 1e-4 to 0.1 s, a mesh with injected
/// slivers, fibers turned 90 degrees or reversed. Each case must reach its last angle in
/// equilibrium or stop with a diagnostic naming the angle, element, node or frame; every
/// array it writes is checked for NaN and infinity.

#include "sim/flexion/knee_flexion.hpp"
#include "sim/verify/stability.hpp"

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace ligsim::sim {

struct FlexionCaseResult {
  std::string name;
  std::string description;
  std::string model; ///< "coarse" or "fine"
  int tets = 0;
  /// converged (static: every angle in equilibrium), completed (interactive: every angle
  /// reached), diagnostic (stopped with a message naming where), skipped (no fine model given)
  /// or failed (a non-finite value written, or a stop without a usable message).
  Outcome outcome = Outcome::failed;
  std::string diagnostic;
  std::vector<AngleResult> angles; ///< the angles reached
  double target_angle_deg = 0.0;
  int iterations = 0; ///< Newton iterations (static) or linear solves (interactive), summed
  double wall_s = 0.0;
  double max_fiber_strain = 0.0; ///< max over elements and angles reached of |F a| - 1
  double min_j = 1.0;
  /// Static cases: the largest, over the angles reached, of |free internal force| / |reactions|
  /// recomputed from the written state (independent of the solver's own figure); NaN if none.
  double equilibrium_residual = 0.0;
  /// The first non-finite value found in the files written ("" when every value is finite).
  std::string non_finite;
  std::string model_change; ///< what was done to the model (slivers, fibers), if anything
};

/// The suite on one or two built models (output folders of `ligsim build`).
class FlexionStabilitySuite {
public:
  /// `base` holds the flexion config's axis, material, in-situ strain and solver settings; the
  /// cases change one thing each. `static_angles_deg`: the quasi-static sweep (default 0, 20,
  /// ..., 140); `fine_model` may be empty (its cases are then skipped).
  FlexionStabilitySuite(FlexionSettings base, std::filesystem::path coarse_model,
                        std::filesystem::path fine_model,
                        std::vector<double> static_angles_deg = {0, 20, 40, 60, 80, 100, 120, 140});
  ~FlexionStabilitySuite();

  const std::vector<double>& static_angles_deg() const { return m_static_angles; }

  /// The cases, in report order.
  static std::vector<StabilityCase> cases();

  /// Runs case `name` (InputError for an unknown one), writing its files into `out / name`.
  FlexionCaseResult run(const std::string& name, const std::filesystem::path& out);

private:
  struct LoadedModel;
  const LoadedModel& model(bool fine);

  FlexionSettings m_base;
  std::filesystem::path m_coarse_dir;
  std::filesystem::path m_fine_dir;
  std::vector<double> m_static_angles;
  std::unique_ptr<LoadedModel> m_coarse;
  std::unique_ptr<LoadedModel> m_fine;
};

/// The first non-finite value in the files of `directory` (VTK XML arrays and points, CSV and
/// JSON numbers, SVG text): "file: array name, entry i", or nullopt when all are finite.
std::optional<std::string> first_non_finite_value(const std::filesystem::path& directory);

/// Flattens element `count` tets of `mesh` (spread over it, their nodes not in `fixed`) to
/// `volume_fraction` of their volume by moving one node towards the opposite face, where no
/// other element inverts. Returns how many became slivers.
int inject_slivers(TetMesh& mesh, int count, double volume_fraction, const std::vector<int>& fixed);

/// case, outcome, iterations, time, max fiber strain, diagnostic (markdown).
std::string flexion_stability_table(const std::vector<FlexionCaseResult>& results);
std::string flexion_stability_csv(const std::vector<FlexionCaseResult>& results);

} // namespace ligsim::sim
