#pragma once
/// @brief Error against run time on the cube (asked for by the user): mesh resolutions, solver
/// tolerances and both linear solvers, each against the finest solution (and against FEBio on
/// its own 16^3 mesh, and against FEBio's quadratic-tet continuum estimate).

#include "common/svg_plot.hpp"
#include "sim/verify/febio_reference.hpp"

#include <functional>
#include <string>
#include <vector>

namespace ligsim::sim {

struct SweepSettings {
  std::vector<int> mesh_cells = {4, 8, 12, 16, 20};
  int finest_cells = 24;
  std::vector<double> tolerances = {1e-2, 1e-4, 1e-6, 1e-8, 1e-10};
  int tolerance_cells = 16;
  /// Relative residual of the mesh family's solves.
  double mesh_tolerance = 1e-8;
  /// Cap on CG iterations per Newton step.
  int pcg_max_iterations = 20000;
};

struct SweepRow {
  std::string family; ///< "mesh" or "tolerance" (or "finest", or "febio": FEBio's own solution)
  int cells = 0;
  std::string linear_solver;
  double tolerance = 0.0;
  bool converged = false;
  std::string failure;
  int elements = 0;
  double wall_s = 0.0;
  int newton_iterations = 0;
  int factorizations = 0;
  int cg_iterations = 0;
  double peak_rss_mib = 0.0;
  /// Node position errors in percent of the edge: against the finest mesh (interpolated at
  /// this mesh's nodes), top face avg / max; against FEBio (only on its 16^3 mesh).
  double avg_error_finest_pct = 0.0;
  double max_error_finest_pct = 0.0;
  double avg_error_febio_pct = -1.0;
  double max_error_febio_pct = -1.0;
  double avg_top_uz_mm = 0.0;
  /// avg_top_uz relative to FEBio's tet10 estimate of the continuum (continuum.json), percent;
  /// absent (NaN) for cases it does not list.
  double continuum_difference_pct = 0.0;
};

/// Runs the sweep on case `c` with its matched energy; every mesh carries the case's total
/// force, shared equally by its top nodes. FEBio's solution (16^3) is a row of its own, with
/// the wall time cases.json records. `on_row` reports progress.
std::vector<SweepRow> run_sweep(const FebioReference& reference, const FebioCase& c,
                                const SweepSettings& settings,
                                const std::function<void(const SweepRow&)>& on_row = {});

std::string sweep_csv(const std::vector<SweepRow>& rows);
std::string sweep_table(const std::vector<SweepRow>& rows);
/// Error against the finest solution over wall time, one series per family and solver, and
/// FEBio's point.
PlotSpec sweep_plot(const std::vector<SweepRow>& rows, const std::string& case_name);

} // namespace ligsim::sim
