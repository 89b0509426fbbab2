#include "sim/verify/cube_verification.hpp"

#include "common/resources.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <ctime>

namespace ligsim::sim {

std::string to_string(CubeEnergy energy)
{
  return energy == CubeEnergy::matched ? "matched" : "paper";
}

MaterialParameters cube_material(const FebioCase& c, CubeEnergy energy)
{
  MaterialParameters material = c.material;
  if (energy == CubeEnergy::paper) {
    material.fiber->convention = FiberConvention::paper;
    material.volumetric = VolumetricLaw::jm1;
  }
  return material;
}

BoundaryConditions cube_conditions(const FebioCase& c, const std::vector<int>& bottom,
                                   const std::vector<int>& top)
{
  BoundaryConditions conditions;
  ConstraintSet fixed;
  fixed.name = "bottom";
  fixed.nodes = bottom;
  conditions.constraints.push_back(fixed);
  NodalLoad load;
  load.name = "top";
  load.nodes = top;
  load.force_per_node_n = c.force_per_top_node_n;
  conditions.loads.push_back(load);
  return conditions;
}

CubeCaseResult run_cube_case(const FebioMesh& mesh, const FebioCase& c, CubeEnergy energy,
                             const NewtonSettings& settings, const Points& reference,
                             double edge_mm, Eigen::VectorXd* x_out)
{
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpu_start = std::clock();
  CubeCaseResult result;
  result.name = c.name;
  result.energy = energy;
  result.incompressibility = c.incompressibility;
  result.febio_wall_s = c.febio.wall_s.value_or(0.0);
  result.load_steps = settings.load_steps;

  FiberField fiber(1, 3);
  fiber.row(0) = c.fiber.normalized().transpose();
  const HyperelasticBody body(mesh.mesh, cube_material(c, energy), fiber);
  const BoundaryConditions conditions = cube_conditions(c, mesh.bottom_nodes, mesh.top_nodes);
  StaticSolver solver(body, conditions, settings);
  Eigen::VectorXd x = body.rest_positions();
  Eigen::VectorXd residual;
  const StaticResult solved = solver.solve(x, [&](const StepReport&, const Eigen::VectorXd&,
                                                  const Eigen::VectorXd& r) { residual = r; });
  result.wall_s = seconds_since(start);
  result.cpu_s = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  result.factorizations = solved.factorizations;
  result.cg_iterations = solved.linear_iterations;
  result.converged = solved.converged;
  result.failure = solved.failure;
  result.newton_iterations = solved.newton_iterations;
  result.projected_elements = solved.projected_elements;
  for (const StepReport& step : solved.steps) {
    result.substeps += step.substeps;
    result.saddle_iterations += step.saddle_iterations;
    if (step.converged_at_floor) {
      result.converged_at_floor = true;
      result.floor = step.floor;
    }
    result.negative_eigenvalues = step.negative_eigenvalues;
    result.instability = step.instability;
  }
  result.cutbacks = solved.cutbacks;
  if (x_out)
    *x_out = x;
  if (!solved.converged)
    return result;

  // Equilibrium: free-DOF residual, and the bottom reactions against the total load.
  const Eigen::Vector3d load = c.force_per_top_node_n * static_cast<double>(mesh.top_nodes.size());
  double free2 = 0.0;
  for (int dof : solver.dofs().free_dofs())
    free2 += residual(dof) * residual(dof);
  result.relative_residual = std::sqrt(free2) / load.norm();
  result.balance_error = (reaction_forces(conditions, residual)[0] + load).norm() / load.norm();

  const Eigen::VectorXd rest = body.rest_positions();
  double top_uz = 0.0;
  for (int node : mesh.top_nodes)
    top_uz += x(3 * node + 2) - rest(3 * node + 2);
  result.avg_top_uz_mm = top_uz / static_cast<double>(mesh.top_nodes.size());
  result.volume_change_pct = 100.0 * (body.volume(x) / body.rest_volume() - 1.0);
  double fiber_strain = 0.0;
  for (Eigen::Index e = 0; e < body.element_count(); ++e)
    fiber_strain += body.element_volume(e) * (body.measures(x, e).deviatoric_fiber_stretch - 1.0);
  result.avg_fiber_strain_pct = 100.0 * fiber_strain / body.rest_volume();

  if (reference.rows() == body.node_count()) {
    auto error_of = [&](int node) {
      const Eigen::Vector3d ours = x.segment<3>(3 * node) - rest.segment<3>(3 * node);
      return 100.0 * (ours - reference.row(node).transpose()).norm() / edge_mm;
    };
    double sum = 0.0;
    for (int node : mesh.top_nodes) {
      const double error = error_of(node);
      sum += error;
      result.max_error_pct = std::max(result.max_error_pct, error);
    }
    result.avg_error_pct = sum / static_cast<double>(mesh.top_nodes.size());
    sum = 0.0;
    for (int node = 0; node < body.node_count(); ++node) {
      const double error = error_of(node);
      sum += error;
      result.max_error_all_pct = std::max(result.max_error_all_pct, error);
    }
    result.avg_error_all_pct = sum / body.node_count();
  }
  return result;
}

namespace {

/// Errors span 1e-7 % (matched energies) to a few percent: keep two significant digits.
std::string percent(double value)
{
  return value >= 0.01 ? fmt::format("{:.3f} %", value) : fmt::format("{:.1e} %", value);
}

} // namespace

std::string cube_equilibrium_table(const std::vector<CubeCaseResult>& results)
{
  std::string table =
      "| case | energy | avg top uz mm | vol. change | relative residual | reaction "
      "balance | Newton it. | sub-steps | cut-backs | indefinite it. | wall s | "
      "stability |\n"
      "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: "
      "| --- |\n";
  for (const CubeCaseResult& r : results) {
    if (!r.converged) {
      table += fmt::format("| {} | {} | failed: {} |\n", r.name, to_string(r.energy), r.failure);
      continue;
    }
    std::string stability = r.negative_eigenvalues > 0 ? r.instability : std::string("stable");
    if (r.converged_at_floor)
      stability += "; converged at the round-off floor: " + r.floor;
    table += fmt::format("| {} | {} | {:.5f} | {:+.2f} % | {:.1e} | {:.1e} | {} | {} | {} | {} | "
                         "{:.2f} | {} |\n",
                         r.name, to_string(r.energy), r.avg_top_uz_mm, r.volume_change_pct,
                         r.relative_residual, r.balance_error, r.newton_iterations, r.substeps,
                         r.cutbacks, r.saddle_iterations, r.wall_s, stability);
  }
  return table;
}

std::string cube_results_table(const std::vector<CubeCaseResult>& results)
{
  std::string table =
      "| case | energy | FEBio incompressibility | avg fiber strain | vol. change | avg error "
      "(top) | max error (top) | avg error (all) | max error (all) | Newton it. | factor. | wall s "
      "| "
      "CPU s | FEBio wall s | speed-up (wall) |\n"
      "| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | "
      "---: | ---: |\n";
  for (const CubeCaseResult& r : results) {
    if (!r.converged) {
      table += fmt::format("| {} | {} | {} | failed: {} |\n", r.name, to_string(r.energy),
                           r.incompressibility, r.failure);
      continue;
    }
    table += fmt::format("| {} | {} | {} | {:+.2f} % | {:+.2f} % | {} | {} | {} | {} | {} | {} | "
                         "{:.2f} | {:.2f} | {:.1f} | {:.0f}x |\n",
                         r.name, to_string(r.energy), r.incompressibility, r.avg_fiber_strain_pct,
                         r.volume_change_pct, percent(r.avg_error_pct), percent(r.max_error_pct),
                         percent(r.avg_error_all_pct), percent(r.max_error_all_pct),
                         r.newton_iterations, r.factorizations, r.wall_s, r.cpu_s, r.febio_wall_s,
                         r.febio_wall_s / std::max(r.wall_s, 1e-9));
  }
  return table;
}

} // namespace ligsim::sim
