#pragma once
/// @brief The two runs every study is made of, as library calls: a model built exactly as
/// `ligsim build` builds it (same stage graph, same cache keys, same summary.json), and a knee
/// flexion sweep on it that keeps, per angle, the figures the studies compare.

#include "pipeline/stage_graph/build_config.hpp"
#include "sim/flexion/flexion_settings.hpp"

#include <Eigen/Core>

#include <filesystem>
#include <string>
#include <vector>

namespace ligsim::study {

/// A model folder after `ligsim build`.
struct BuiltModel {
  std::filesystem::path dir;
  double build_s = 0.0;      ///< wall time of every stage (a reused stage counts its first run)
  double peak_rss_mib = 0.0; ///< the largest stage peak (the same for reused stages)
  bool reused = false;       ///< every stage was current
  int tets = 0;
  int nodes = 0;
};

/// Runs the stage graph into `dir` (stages that are current are reused) and writes its
/// summary.json, as `ligsim build --out dir` with `config` would. Throws what the stages throw.
BuiltModel build_model(const pipeline::BuildConfig& config, const std::filesystem::path& dir);

/// The figures of one flexion angle.
struct AngleFigures {
  double angle_deg = 0.0;
  double strain_energy_mj = 0.0;
  double mean_fiber_stretch = 0.0; ///< volume-weighted |F a|, pre-stretch included
  double p95_fiber_stretch = 0.0;  ///< volume-weighted 95th percentile
  double max_fiber_stretch = 0.0;
  Eigen::Vector3d femur_force_n = Eigen::Vector3d::Zero();
};

/// A flexion sweep with its cost.
struct FlexionFigures {
  bool success = false;
  std::string failure;
  std::vector<AngleFigures> angles;
  double setup_s = 0.0;           ///< reading the model, fitting the axis, building the body
  double solve_s = 0.0;           ///< the sweep alone (measuring excluded)
  double peak_rss_mib = 0.0;      ///< setup and sweep
  int frames = 0;                 ///< interactive: implicit Euler frames; quasi-static: angles
  double frames_per_second = 0.0; ///< interactive: frames over their own time
  double time_step_s = 0.0;       ///< interactive: the time step used
  int tets = 0;
};

/// Runs the sweep of `settings` on the model in `settings.model_dir` (no files written, no
/// pictures). Never throws on divergence: `success` and `failure` say where it stopped.
FlexionFigures run_flexion(const sim::FlexionSettings& settings);

/// The volume-weighted `fraction` quantile of `values` (weights `volumes`, positive).
double weighted_quantile(const std::vector<double>& values, const std::vector<double>& volumes,
                         double fraction);

} // namespace ligsim::study
