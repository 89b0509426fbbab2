#include "sim/verify/stability.hpp"

#include "common/error.hpp"
#include "common/resources.hpp"
#include "sim/mesh/node_selection.hpp"
#include "sim/mesh/structured_mesh.hpp"
#include "sim/mesh/tet_shape.hpp"
#include "sim/solver/arc_length.hpp"
#include "sim/solver/implicit_euler.hpp"
#include "sim/solver/static_solver.hpp"
#include "sim/verify/contact_stability.hpp"

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <limits>

namespace ligsim::sim {

namespace {

/// The paper's largest total load on the 1 mm cube: 0.2 N on each of 289 top nodes.
constexpr double paper_largest_total_n = 0.2 * 289;

struct CubeSetup {
  TetMesh mesh;
  MaterialParameters material = mcl_material();
  Eigen::Vector3d fiber = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d total_load_n = Eigen::Vector3d(0, 0, paper_largest_total_n);
  NewtonSettings newton;
  /// Set for a dynamic case.
  std::optional<DynamicsSettings> dynamics;
  /// Follow the path by arc-length continuation instead of load control.
  bool arc_length = false;
};

/// The critical points an arc-length path met, in one line ("" when none).
std::string describe_critical_points(const ArcLengthResult& run)
{
  std::string text;
  for (const CriticalPoint& point : run.critical_points) {
    const PathPoint& after = run.path[static_cast<std::size_t>(point.step)];
    const PathPoint& before = run.path[static_cast<std::size_t>(point.step) - 1];
    text += fmt::format("{}{} at load factor {:.4g} (between path points at {:.4g} and {:.4g}; "
                        "negative eigenvalues {} -> {})",
                        text.empty() ? "" : "; ", point.kind, point.load_factor, point.bracket_from,
                        point.bracket_to, before.negative_eigenvalues, after.negative_eigenvalues);
  }
  return text;
}

CubeSetup default_setup(int cells)
{
  CubeSetup setup;
  setup.mesh = structured_cube_mesh(cells, 1.0);
  setup.newton.load_steps = 2;
  return setup;
}

/// Moves node `node` of the cube so that element `e` becomes a sliver: its node is pushed to
/// within a small fraction of the element's height from the opposite face.
void make_sliver(TetMesh& mesh, int& element)
{
  // An interior node: the middle of the cube.
  const int n = static_cast<int>(std::round(std::cbrt(static_cast<double>(mesh.V.rows())))) - 1;
  const int middle = n / 2 + (n + 1) * (n / 2 + (n + 1) * (n / 2));
  for (Eigen::Index e = 0; e < mesh.T.rows(); ++e)
    for (int i = 0; i < 4; ++i)
      if (mesh.T(e, i) == middle) {
        element = static_cast<int>(e);
        // Move the node toward the opposite face's plane: the element keeps 2 % of its volume.
        mesh.V.row(middle) = toward_opposite_face(mesh, e, i, 0.02).transpose();
        return;
      }
}

StabilityResult run_setup(const CubeSetup& setup)
{
  StabilityResult result;
  const auto start = std::chrono::steady_clock::now();
  try {
    FiberField fiber(1, 3);
    fiber.row(0) = setup.fiber.transpose();
    const HyperelasticBody body(setup.mesh, setup.material, fiber);
    BoundaryConditions conditions;
    ConstraintSet bottom;
    bottom.name = "bottom";
    bottom.nodes = nodes_on_plane(setup.mesh.V, 2, 0.0, 1e-9);
    conditions.constraints.push_back(bottom);
    NodalLoad load;
    load.name = "top";
    load.nodes = nodes_on_plane(setup.mesh.V, 2, 1.0, 1e-9);
    load.force_per_node_n = setup.total_load_n / static_cast<double>(load.nodes.size());
    conditions.loads.push_back(load);

    Eigen::VectorXd x = body.rest_positions();
    Eigen::VectorXd residual;
    if (setup.dynamics) {
      ImplicitEuler solver(body, conditions, *setup.dynamics);
      const DynamicResult run = solver.run(x, [&](const FrameReport&, const Eigen::VectorXd&,
                                                  const Eigen::VectorXd& r) { residual = r; });
      result.converged = run.completed;
      result.diagnostic = run.failure;
      result.iterations = run.frames;
    } else if (setup.arc_length) {
      const BodyEquilibrium system(body, conditions);
      Eigen::VectorXd u = system.rest_unknowns();
      const ArcLengthResult run = follow_path(system, u);
      x = system.positions(u);
      result.converged = run.reached;
      result.iterations = run.newton_iterations;
      result.diagnostic = run.reached ? describe_critical_points(run) : run.failure;
      body.energy_gradient(x, residual);
      residual -= DofPartition(body.node_count(), conditions, body.unreferenced_nodes())
                      .external_forces(conditions);
    } else {
      StaticSolver solver(body, conditions, setup.newton);
      const StaticResult run = solver.solve(x, [&](const StepReport&, const Eigen::VectorXd&,
                                                   const Eigen::VectorXd& r) { residual = r; });
      result.converged = run.converged;
      result.diagnostic = run.failure;
      result.iterations = run.newton_iterations;
      if (run.converged && !run.steps.empty() && run.steps.back().negative_eigenvalues > 0)
        result.diagnostic = run.steps.back().instability; // converged, but unstable
    }
    result.min_j = body.min_j(x).first;
    const Eigen::VectorXd rest = body.rest_positions();
    for (int node = 0; node < body.node_count(); ++node)
      result.max_displacement_mm = std::max(
          result.max_displacement_mm, (x.segment<3>(3 * node) - rest.segment<3>(3 * node)).norm());
    if (!setup.dynamics && result.converged && residual.size() == x.size()) {
      const Eigen::Vector3d reaction = reaction_forces(conditions, residual)[0];
      result.balance_error = (reaction + setup.total_load_n).norm() / setup.total_load_n.norm();
    }
    if (setup.dynamics && result.converged && x.allFinite() && std::isfinite(result.min_j))
      result.outcome = Outcome::completed;
    else
      result.outcome = static_outcome(result, x);
  } catch (const Error& e) {
    result.diagnostic = e.what();
    result.outcome = Outcome::diagnostic;
  }
  result.wall_s = seconds_since(start);
  return result;
}

struct CaseDefinition {
  StabilityCase info;
  std::function<void(CubeSetup&)> adjust;
};

std::vector<CaseDefinition> definitions()
{
  std::vector<CaseDefinition> list;
  for (double k : {1e2, 1e3, 1e4, 1e5, 1e6})
    list.push_back({{fmt::format("bulk_modulus_{:.0e}", k),
                     fmt::format("K = {:.0e} MPa, 0.2 N per node (paper's largest load)", k)},
                    [k](CubeSetup& s) { s.material.bulk_modulus_mpa = k; }});
  for (double c5 : {1e3, 1e4})
    list.push_back(
        {{fmt::format("c5_{:.0e}", c5), fmt::format("C5 = {:.0e} MPa, 0.2 N per node", c5)},
         [c5](CubeSetup& s) { s.material.fiber->c5_mpa = c5; }});
  list.push_back({{"load_x10", "2 N per node: ten times the paper's largest load"},
                  [](CubeSetup& s) { s.total_load_n *= 10.0; }});
  list.push_back(
      {{"compression_0.05", "compression along the fibers, 0.05 N per node"}, [](CubeSetup& s) {
         s.total_load_n = {0, 0, -0.05 * 289};
       }});
  list.push_back(
      {{"compression_0.20", "compression along the fibers, 0.2 N per node"}, [](CubeSetup& s) {
         s.total_load_n = {0, 0, -0.2 * 289};
       }});
  list.push_back({{"compression_0.20_arc_length",
                   "compression along the fibers, 0.2 N per node, by arc-length continuation: "
                   "where the straight column's tangent turns indefinite"},
                  [](CubeSetup& s) {
                    s.total_load_n = {0, 0, -0.2 * 289};
                    s.arc_length = true;
                  }});
  for (double dt : {1e-5, 1e-3, 1e-1, 1.0})
    list.push_back({{fmt::format("dynamic_dt_{:.0e}", dt),
                     fmt::format("implicit Euler, time step {:.0e} s, 40 frames, 0.2 N per node "
                                 "ramped over 10 frames",
                                 dt)},
                    [dt](CubeSetup& s) {
                      DynamicsSettings dynamics;
                      dynamics.time_step_s = dt;
                      dynamics.frames = 40;
                      dynamics.ramp_frames = 10;
                      dynamics.linear_solver = LinearSolverKind::direct;
                      s.dynamics = dynamics;
                    }});
  list.push_back({{"inverted_element", "element 0 inverted in the rest shape"},
                  [](CubeSetup& s) { std::swap(s.mesh.T(0, 0), s.mesh.T(0, 1)); }});
  list.push_back(
      {{"sliver", "a sliver: one element squashed to 2 % of its volume"}, [](CubeSetup& s) {
         int element = -1;
         make_sliver(s.mesh, element);
       }});
  list.push_back({{"nan_node", "node 5 moved to NaN"},
                  [](CubeSetup& s) { s.mesh.V(5, 1) = std::numeric_limits<double>::quiet_NaN(); }});
  return list;
}

} // namespace

Outcome static_outcome(const StabilityResult& result, const Eigen::VectorXd& x, bool check)
{
  const bool finite = x.allFinite() && std::isfinite(result.min_j);
  if (result.converged && finite && result.balance_error < 1e-6 && check)
    return Outcome::converged;
  if (!result.converged && finite && !result.diagnostic.empty())
    return Outcome::diagnostic;
  return Outcome::failed;
}

std::vector<StabilityCase> stability_cases()
{
  std::vector<StabilityCase> cases;
  for (const CaseDefinition& d : definitions())
    cases.push_back(d.info);
  for (const StabilityCase& c : contact_stability_cases()) // sim/verify/contact_stability.cpp
    cases.push_back(c);
  return cases;
}

StabilityResult run_stability_case(const std::string& name, int cells)
{
  for (const CaseDefinition& d : definitions()) {
    if (d.info.name != name)
      continue;
    CubeSetup setup = default_setup(cells);
    d.adjust(setup);
    StabilityResult result = run_setup(setup);
    result.name = d.info.name;
    result.description = d.info.description;
    return result;
  }
  if (std::optional<StabilityResult> contact = run_contact_stability_case(name))
    return *contact;
  fail("unknown stability case '{}'", name);
}

std::string stability_table(const std::vector<StabilityResult>& results)
{
  std::string table = "| case | set-up | outcome | iterations / frames | wall s | worst J | max "
                      "displacement mm | reaction balance | diagnostic |\n"
                      "| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | --- |\n";
  for (const StabilityResult& r : results)
    table += fmt::format("| {} | {} | {} | {} | {:.2f} | {:.4f} | {:.4f} | {:.1e} | {} |\n", r.name,
                         r.description, to_string(r.outcome), r.iterations, r.wall_s, r.min_j,
                         r.max_displacement_mm, r.balance_error,
                         r.diagnostic.empty() ? "-" : r.diagnostic);
  return table;
}

} // namespace ligsim::sim
