#pragma once
/// @brief The two runs every study is made of, as library calls: a model (one ligament or a
/// knee) built exactly as `ligsim build` builds it (same stage graph, same cache keys, same
/// summary.json), and a knee flexion sweep on it that keeps, per ligament and angle, the figures
/// the studies compare.

#include "pipeline/study/study_model.hpp"
#include "sim/flexion/flexion_settings.hpp"

#include <Eigen/Core>

#include <filesystem>
#include <string>
#include <vector>

namespace ligsim::study {

/// One ligament's stages in a model folder after `ligsim build`.
struct BuiltLigament {
  double build_s = 0.0;      ///< wall time of its stages (a reused stage counts its first run)
  double peak_rss_mib = 0.0; ///< the largest stage peak (the same for reused stages)
  int tets = 0;
  int nodes = 0;
  std::string failure; ///< a knee's ligament that could not be built: why (the knee goes on)
};

/// A model folder after `ligsim build`.
struct BuiltModel {
  std::filesystem::path dir;
  std::vector<BuiltLigament> ligaments; ///< in the order of StudyModel's ligaments

  /// Whether some ligament was built (a knee with none has no knee.json to sweep).
  bool any_built() const;
};

/// Runs the stage graph of every ligament into `dir` (stages that are current are reused) and
/// writes summary.json (and, for a knee, the bones and knee.json), as `ligsim build --out dir`
/// with the config would; except that a knee's ligament that cannot be built is left out of
/// knee.json with its failure, so that one ligament's failure leaves the others' figures (none
/// built: no knee.json). Throws what the stages throw for a one-ligament config.
BuiltModel build_model(const StudyModel& model, const std::filesystem::path& dir);

/// The figures of one flexion angle.
struct AngleFigures {
  double angle_deg = 0.0;
  double strain_energy_mj = 0.0;
  double mean_fiber_stretch = 0.0; ///< volume-weighted |F a|, pre-stretch included
  double p95_fiber_stretch = 0.0;  ///< volume-weighted 95th percentile
  double max_fiber_stretch = 0.0;
  /// The largest mean fiber stretch over a region of the settings' radius (2 mm by default)
  double regional_fiber_stretch = 0.0;
  Eigen::Vector3d femur_force_n = Eigen::Vector3d::Zero();
};

/// One ligament's flexion sweep with its cost.
struct FlexionFigures {
  std::string ligament; ///< its name (a one-ligament model: the flexion settings' name)
  bool success = false;
  std::string failure;
  std::vector<AngleFigures> angles;
  double setup_s = 0.0;      ///< reading the model, fitting the axis, building this ligament's body
  double solve_s = 0.0;      ///< the sweep alone (measuring excluded)
  double peak_rss_mib = 0.0; ///< the process' peak up to the end of this sweep
  int frames = 0;            ///< interactive: implicit Euler frames; quasi-static: angles
  double frames_per_second = 0.0; ///< interactive: frames over their own time
  double time_step_s = 0.0;       ///< interactive: the time step used
  int tets = 0;
};

/// Runs the sweep of `settings` on every ligament of the model in `settings.model_dir` (those
/// `settings.ligaments` names in a knee), each with its own material and in-situ strain as
/// `ligsim flexion` gives it, against no bone (no files written, no pictures); a [ligament]
/// table naming a ligament the knee lacks is set aside. Never throws on divergence: each
/// ligament's `success` and `failure` say where it stopped.
std::vector<FlexionFigures> run_flexion(const sim::FlexionSettings& settings);

/// The figures of the ligament called `name`, null when the sweep has none.
const FlexionFigures* figures_of(const std::vector<FlexionFigures>& figures,
                                 const std::string& name);

/// The volume-weighted `fraction` quantile of `values` (weights `volumes`, positive).
double weighted_quantile(const std::vector<double>& values, const std::vector<double>& volumes,
                         double fraction);

} // namespace ligsim::study
