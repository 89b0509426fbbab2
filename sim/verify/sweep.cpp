#include "sim/verify/sweep.hpp"

#include "common/error.hpp"
#include "common/resources.hpp"
#include "sim/mesh/tet_shape.hpp"
#include "sim/verify/cube_compression.hpp"
#include "sim/verify/cube_verification.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>

namespace ligsim::sim {

namespace {

/// Top-face nodes of FEBio's 16 x 16 x 16 reference mesh, on which the cases' per-node forces
/// are defined.
constexpr int febio_top_nodes = 17 * 17;

/// A solved structured cube: its mesh, node sets and displacements.
struct CubeSolution {
  int cells = 0;
  FebioMesh mesh;
  Points displacement;
};

/// Displacement of the finest solution at `p`, by barycentric interpolation in the tet of the
/// structured grid that contains it.
Eigen::Vector3d sample(const CubeSolution& finest, double edge_mm, const Eigen::Vector3d& p)
{
  const int n = finest.cells;
  Eigen::Vector3i cell;
  for (int a = 0; a < 3; ++a)
    cell(a) = std::clamp(static_cast<int>(std::floor(p(a) / edge_mm * n)), 0, n - 1);
  const int hex = cell.x() + n * (cell.y() + n * cell.z());
  const Tetrahedra& T = finest.mesh.mesh.T;
  int best = -1;
  double best_min = -std::numeric_limits<double>::infinity();
  Eigen::Vector4d best_weights;
  for (int e = 5 * hex; e < 5 * hex + 5; ++e) {
    TetCorners P;
    for (int i = 0; i < 4; ++i)
      P.row(i) = finest.mesh.mesh.V.row(T(e, i));
    const TetShape shape = tet_shape(P);
    Eigen::Vector4d weights = shape.D * (p - P.row(0).transpose());
    weights(0) += 1.0;
    if (weights.minCoeff() > best_min) {
      best_min = weights.minCoeff();
      best = e;
      best_weights = weights;
    }
  }
  Eigen::Vector3d u = Eigen::Vector3d::Zero();
  for (int i = 0; i < 4; ++i)
    u += best_weights(i) * finest.displacement.row(T(best, i)).transpose();
  return u;
}

std::optional<double> continuum_top_uz(const FebioReference& reference, const std::string& name)
{
  std::ifstream in(reference.directory / "continuum.json");
  if (!in)
    return std::nullopt;
  const nlohmann::json continuum = nlohmann::json::parse(in, nullptr, false);
  if (continuum.is_discarded() || !continuum.contains("cases"))
    return std::nullopt;
  // continuum.json names cases without the incompressibility suffix ("par_t005").
  const std::string stem = name.substr(0, name.rfind('_'));
  if (!continuum["cases"].contains(stem))
    return std::nullopt;
  return continuum["cases"][stem].value("avg_top_uz", 0.0);
}

CubeSolution solve_cube(int cells, const FebioCase& c, const NewtonSettings& settings,
                        double edge_mm, SweepRow& row, const Points& febio)
{
  CubeSolution solution;
  solution.cells = cells;
  solution.mesh = structured_cube(cells, edge_mm);
  // The case's total force (its per-node force on FEBio's 17 x 17 top nodes), shared equally
  // by this mesh's top nodes.
  FebioCase scaled = c;
  scaled.force_per_top_node_n *=
      static_cast<double>(febio_top_nodes) / static_cast<double>(solution.mesh.top_nodes.size());
  Eigen::VectorXd x;
  reset_peak_rss();
  const CubeCaseResult result = run_cube_case(solution.mesh, scaled, CubeEnergy::matched, settings,
                                              cells == 16 ? febio : Points(), edge_mm, &x);
  row.cells = cells;
  row.elements = static_cast<int>(solution.mesh.mesh.T.rows());
  row.converged = result.converged;
  row.failure = result.failure;
  row.wall_s = result.wall_s;
  row.peak_rss_mib = peak_rss_mib();
  row.newton_iterations = result.newton_iterations;
  row.factorizations = result.factorizations;
  row.cg_iterations = result.cg_iterations;
  row.avg_top_uz_mm = result.avg_top_uz_mm;
  if (cells == 16 && result.converged) {
    row.avg_error_febio_pct = result.avg_error_pct;
    row.max_error_febio_pct = result.max_error_pct;
  }
  solution.displacement =
      Eigen::Map<const Points>(x.data(), solution.mesh.mesh.V.rows(), 3) - solution.mesh.mesh.V;
  return solution;
}

void compare_with_finest(const CubeSolution& solution, const CubeSolution& finest, double edge_mm,
                         SweepRow& row)
{
  double sum = 0.0;
  double worst = 0.0;
  for (int node : solution.mesh.top_nodes) {
    const Eigen::Vector3d p = solution.mesh.mesh.V.row(node);
    const double error =
        100.0 * (solution.displacement.row(node).transpose() - sample(finest, edge_mm, p)).norm() /
        edge_mm;
    sum += error;
    worst = std::max(worst, error);
  }
  row.avg_error_finest_pct = sum / static_cast<double>(solution.mesh.top_nodes.size());
  row.max_error_finest_pct = worst;
}

} // namespace

std::vector<SweepRow> run_sweep(const FebioReference& reference, const FebioCase& c,
                                const SweepSettings& settings,
                                const std::function<void(const SweepRow&)>& on_row)
{
  const double edge = reference.edge_mm;
  const Points febio =
      read_febio_displacements(c.displacements, structured_cube(16, edge).mesh.V.rows());
  const std::optional<double> continuum = continuum_top_uz(reference, c.name);
  auto finish = [&](SweepRow& row) {
    row.continuum_difference_pct = continuum ? 100.0 * (row.avg_top_uz_mm / *continuum - 1.0)
                                             : std::numeric_limits<double>::quiet_NaN();
    if (on_row)
      on_row(row);
  };

  NewtonSettings base;
  base.load_steps = 1;
  base.pcg.max_iterations = settings.pcg_max_iterations;
  base.pcg.tolerance = 1e-8;

  std::vector<SweepRow> rows;
  SweepRow finest_row;
  finest_row.family = "finest";
  finest_row.linear_solver = "direct";
  finest_row.tolerance = 1e-10;
  NewtonSettings finest_settings = base;
  finest_settings.residual_tolerance = finest_row.tolerance;
  const CubeSolution finest =
      solve_cube(settings.finest_cells, c, finest_settings, edge, finest_row, febio);
  if (!finest_row.converged)
    fail<SolverError>("sweep: the finest mesh ({} cells) did not converge: {}",
                      settings.finest_cells, finest_row.failure);
  finish(finest_row);
  rows.push_back(finest_row);

  // FEBio's own solution on its 16^3 mesh at the wall time it recorded (cases.json): the point
  // that answers "same error, how much less time".
  if (c.febio.wall_s) {
    SweepRow row;
    row.family = "febio";
    row.linear_solver = "FEBio";
    row.cells = 16;
    row.converged = true;
    row.wall_s = *c.febio.wall_s;
    const CubeSolution solution{16, structured_cube(16, edge), febio};
    row.elements = static_cast<int>(solution.mesh.mesh.T.rows());
    for (int node : solution.mesh.top_nodes)
      row.avg_top_uz_mm += febio(node, 2) / static_cast<double>(solution.mesh.top_nodes.size());
    compare_with_finest(solution, finest, edge, row);
    finish(row);
    rows.push_back(row);
  }

  for (LinearSolverKind kind : {LinearSolverKind::direct, LinearSolverKind::pcg}) {
    for (int cells : settings.mesh_cells) {
      SweepRow row;
      row.family = "mesh";
      row.linear_solver = to_string(kind);
      row.tolerance = settings.mesh_tolerance;
      NewtonSettings newton = base;
      newton.linear_solver = kind;
      newton.residual_tolerance = settings.mesh_tolerance;
      const CubeSolution solution = solve_cube(cells, c, newton, edge, row, febio);
      if (row.converged)
        compare_with_finest(solution, finest, edge, row);
      finish(row);
      rows.push_back(row);
    }
    for (double tolerance : settings.tolerances) {
      SweepRow row;
      row.family = "tolerance";
      row.linear_solver = to_string(kind);
      row.tolerance = tolerance;
      NewtonSettings newton = base;
      newton.linear_solver = kind;
      newton.residual_tolerance = tolerance;
      // A loose Newton tolerance deserves an equally loose CG tolerance.
      newton.pcg.tolerance = std::min(1e-2, std::max(1e-10, 0.01 * tolerance));
      const CubeSolution solution =
          solve_cube(settings.tolerance_cells, c, newton, edge, row, febio);
      if (row.converged)
        compare_with_finest(solution, finest, edge, row);
      finish(row);
      rows.push_back(row);
    }
  }
  return rows;
}

std::string sweep_csv(const std::vector<SweepRow>& rows)
{
  std::string csv = "family,cells,elements,linear_solver,tolerance,converged,wall_s,peak_rss_mib,"
                    "newton_iterations,factorizations,cg_iterations,avg_error_finest_pct,"
                    "max_error_finest_pct,avg_error_febio_pct,max_error_febio_pct,avg_top_uz_mm,"
                    "continuum_difference_pct\n";
  for (const SweepRow& r : rows)
    csv += fmt::format(
        "{},{},{},{},{:g},{},{:.4f},{:.1f},{},{},{},{:.6g},{:.6g},{},{},{:.8g},{:.4g}\n", r.family,
        r.cells, r.elements, r.linear_solver, r.tolerance, r.converged ? 1 : 0, r.wall_s,
        r.peak_rss_mib, r.newton_iterations, r.factorizations, r.cg_iterations,
        r.avg_error_finest_pct, r.max_error_finest_pct,
        r.avg_error_febio_pct < 0 ? "" : fmt::format("{:.6g}", r.avg_error_febio_pct),
        r.max_error_febio_pct < 0 ? "" : fmt::format("{:.6g}", r.max_error_febio_pct),
        r.avg_top_uz_mm, r.continuum_difference_pct);
  return csv;
}

std::string sweep_table(const std::vector<SweepRow>& rows)
{
  std::string table =
      "| family | cells | elements | solver | tolerance | wall s | peak MiB | Newton | factor. | "
      "CG it. | avg err vs finest | max err vs finest | avg err vs FEBio | max err vs FEBio | "
      "avg top uz mm | vs continuum |\n"
      "| --- | ---: | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | "
      "---: | ---: | ---: |\n";
  auto pct = [](double v) { return v < 0 ? std::string("-") : fmt::format("{:.2e} %", v); };
  for (const SweepRow& r : rows) {
    if (!r.converged) {
      table += fmt::format("| {} | {} | {} | {} | {:g} | {:.2f} | failed: {} |\n", r.family,
                           r.cells, r.elements, r.linear_solver, r.tolerance, r.wall_s, r.failure);
      continue;
    }
    table += fmt::format("| {} | {} | {} | {} | {:g} | {:.2f} | {:.0f} | {} | {} | {} | {} | {} | "
                         "{} | {} | {:.5f} | {:+.2f} % |\n",
                         r.family, r.cells, r.elements, r.linear_solver, r.tolerance, r.wall_s,
                         r.peak_rss_mib, r.newton_iterations, r.factorizations, r.cg_iterations,
                         r.family == "finest" ? "-" : pct(r.avg_error_finest_pct),
                         r.family == "finest" ? "-" : pct(r.max_error_finest_pct),
                         pct(r.avg_error_febio_pct), pct(r.max_error_febio_pct), r.avg_top_uz_mm,
                         r.continuum_difference_pct);
  }
  return table;
}

PlotSpec sweep_plot(const std::vector<SweepRow>& rows, const std::string& case_name)
{
  PlotSpec spec;
  spec.title = "Cube " + case_name + ": error against run time";
  spec.x_label = "wall time per solve, s";
  spec.y_label = "avg top-face error vs finest mesh, % of edge";
  spec.log_x = true;
  spec.log_y = true;
  for (const std::string family : {"mesh", "tolerance"})
    for (const std::string solver : {"direct", "pcg"}) {
      PlotSeries series;
      series.name = family == "mesh" ? "mesh refinement, " + solver : "tolerance (16^3), " + solver;
      for (const SweepRow& r : rows)
        if (r.family == family && r.linear_solver == solver && r.converged) {
          series.x.push_back(r.wall_s);
          series.y.push_back(r.avg_error_finest_pct);
          series.point_labels.push_back(family == "mesh" ? fmt::format("n={}", r.cells)
                                                         : fmt::format("{:g}", r.tolerance));
        }
      spec.series.push_back(series);
    }
  PlotSeries febio;
  febio.name = "FEBio 4.11 (recorded time)";
  for (const SweepRow& r : rows)
    if (r.family == "febio") {
      febio.x.push_back(r.wall_s);
      febio.y.push_back(r.avg_error_finest_pct);
      febio.point_labels.push_back("FEBio n=16");
    }
  if (!febio.x.empty())
    spec.series.push_back(febio);
  return spec;
}

} // namespace ligsim::sim
