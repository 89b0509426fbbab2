#include "pipeline/scenes/scene_runner.hpp"

#include "pipeline/reports/step_report_json.hpp"

#include "common/atomic_file.hpp"
#include "common/progress.hpp"
#include "common/resources.hpp"
#include "common/run_summary.hpp"
#include "sim/contact/bone_level_set.hpp"
#include "sim/contact/contact_potential.hpp"
#include "sim/contact/contact_surface.hpp"
#include "sim/mesh/quadratic_tet.hpp"
#include "sim/scene/scene_output.hpp"
#include "stages/io/surface_reader.hpp"

#include <fmt/format.h>

#include <memory>

namespace ligsim::scenes {

using namespace sim;

namespace fs = std::filesystem;

namespace {

/// Reaction force (and, for rigid motions, moment about the rotation point) of every set.
nlohmann::json reactions_json(const BoundaryConditions& conditions, const Eigen::VectorXd& x,
                              const Eigen::VectorXd& residual, std::string& csv,
                              const std::string& row_prefix)
{
  nlohmann::json reactions = nlohmann::json::object();
  const std::vector<Eigen::Vector3d> forces = reaction_forces(conditions, residual);
  for (std::size_t s = 0; s < forces.size(); ++s) {
    const ConstraintSet& set = conditions.constraints[s];
    nlohmann::json entry = {{"force_n", json_vector3(forces[s])},
                            {"magnitude_n", forces[s].norm()}};
    if (set.rigid)
      entry["moment_nmm"] = json_vector3(reaction_moment(set, residual, x, set.rigid->point_mm));
    reactions[set.name] = entry;
    csv += fmt::format("{},{},{:.9g},{:.9g},{:.9g},{:.9g}\n", row_prefix, set.name, forces[s].x(),
                       forces[s].y(), forces[s].z(), forces[s].norm());
  }
  return reactions;
}

/// The scene's bones as contact obstacles: level sets cached in the output folder's contact/.
struct SceneContact {
  std::vector<std::unique_ptr<BoneLevelSet>> grids;
  std::unique_ptr<ContactPotential> potential;
  nlohmann::json figures;
};

std::unique_ptr<SceneContact> scene_contact(const Scene& scene, const fs::path& out)
{
  if (scene.bones.empty() || !scene.contact.enabled.value_or(true))
    return nullptr;
  const fs::path cache = out / "contact";
  auto contact = std::make_unique<SceneContact>();
  std::vector<ContactObstacle> obstacles;
  for (const SceneBone& bone : scene.bones) {
    const TriangleSurface surface = io::read_surface(bone.surface);
    contact->grids.push_back(
        BoneLevelSet::cached(surface, scene.contact.grid, cache / (bone.name + ".vdb")));
    ContactObstacle obstacle{bone.name, contact->grids.back().get(), std::nullopt, {}};
    for (const ConstraintSet& set : scene.conditions.constraints)
      if (!bone.follows.empty() && set.name == bone.follows) {
        obstacle.motion = set.rigid;
        obstacle.excluded_nodes = set.nodes;
      }
    const LevelSetFigures& grid = contact->grids.back()->figures();
    contact->figures[bone.name] = {{"surface", bone.surface.string()},
                                   {"follows", bone.follows},
                                   {"reused", grid.reused},
                                   {"build_s", grid.build_s},
                                   {"active_voxels", grid.active_voxels}};
    obstacles.push_back(obstacle);
  }
  contact->potential = std::make_unique<ContactPotential>(
      static_cast<int>(scene.mesh.V.rows()),
      free_boundary_surface(scene.mesh, scene.conditions,
                            scene.tet10.rows() > 0 ? &scene.tet10 : nullptr),
      std::move(obstacles), scene.contact.barrier);
  contact->figures["d_hat_mm"] = scene.contact.barrier.d_hat_mm;
  contact->figures["stiffness_mpa_per_mm"] = scene.contact.barrier.stiffness_mpa_per_mm;
  return contact;
}

/// Per bone contact force, area and smallest gap at (x, t); the per node arrays for the VTU.
nlohmann::json contact_json(const SceneContact* contact, const Eigen::VectorXd& x, double t,
                            PointArrays& arrays)
{
  arrays.clear();
  if (!contact)
    return nullptr;
  const ContactMeasures m = contact->potential->measure(x, t);
  nlohmann::json bones = nlohmann::json::object();
  for (std::size_t o = 0; o < m.force_n.size(); ++o)
    bones[contact->potential->obstacles()[o].name] = {{"force_n", json_vector3(m.force_n[o])},
                                                      {"area_mm2", m.area_mm2[o]},
                                                      {"nodes", m.active_nodes[o]},
                                                      {"min_gap_mm", m.min_gap_mm[o]}};
  arrays = {{"gap_mm", m.gap_mm}, {"contact_pressure", m.pressure_mpa}};
  return bones;
}

} // namespace

SceneRunReport run_scene(const Scene& scene, const fs::path& out, RunSummary& summary)
{
  ensure_directory(out);
  StageMeter setup_meter;
  const HyperelasticBody body =
      scene.tet10.rows() == 0
          ? HyperelasticBody(scene.mesh, scene.material, scene.fibers)
          : HyperelasticBody(QuadraticTetMesh{scene.mesh.V, scene.tet10}, scene.material,
                             scene.fibers, tet_quadrature(kQuadraticTetRuleDegree));
  const std::unique_ptr<SceneContact> contact = scene_contact(scene, out);
  summary.add_stage("setup", setup_meter,
                    {{"nodes", body.node_count()},
                     {"elements", body.element_count()},
                     {"fibers", body.material().has_fibers()},
                     {"rest_volume_mm3", body.rest_volume()},
                     {"contact", contact ? contact->figures : nlohmann::json("off")}});
  PointArrays contact_arrays;

  std::unique_ptr<SceneOutput> output;
  if (scene.output.vtu)
    output = std::make_unique<SceneOutput>(body, out);
  std::string csv = scene.kind == SceneKind::quasi_static
                        ? "step,load_factor,set,fx_n,fy_n,fz_n,magnitude_n\n"
                        : "frame,time_s,set,fx_n,fy_n,fz_n,magnitude_n\n";
  nlohmann::json entries = nlohmann::json::array();
  SceneRunReport run;
  StageMeter solve_meter;
  nlohmann::json solve_figures;
  // One step or frame: its report with the reactions at `number` and `at` (load factor or time)
  // into summary.json and the CSV, the contact's figures, and, when `write`, its state.
  const auto record = [&](nlohmann::json entry, int number, double at, double load_factor,
                          const Eigen::VectorXd& state, const Eigen::VectorXd& residual,
                          bool write) {
    entry["reactions"] =
        reactions_json(scene.conditions, state, residual, csv, fmt::format("{},{}", number, at));
    if (contact)
      entry["contact"] = contact_json(contact.get(), state, load_factor, contact_arrays);
    entries.push_back(entry);
    if (output && write)
      output->write_step(number, at, state, contact_arrays);
  };

  if (scene.kind == SceneKind::quasi_static) {
    StaticSolver solver(body, scene.conditions, scene.newton);
    if (contact)
      solver.set_extra_potential(contact->potential.get());
    Eigen::VectorXd x = body.rest_positions();
    if (output)
      output->write_step(0, 0.0, x);
    Progress progress("load steps", static_cast<std::size_t>(scene.newton.load_steps));
    const StaticResult result =
        solver.solve(x, [&](const StepReport& step, const Eigen::VectorXd& state,
                            const Eigen::VectorXd& residual) {
          const bool last = step.step == scene.newton.load_steps;
          record(reports::to_json(step), step.step, step.load_factor, step.load_factor, state,
                 residual, step.step % scene.output.every == 0 || last);
          progress.advance();
        });
    progress.finish();
    run.success = result.converged;
    run.failure = result.failure;
    solve_figures = {{"converged", result.converged},
                     {"stop_kind", result.stop_kind},
                     {"newton_iterations", result.newton_iterations},
                     {"cutbacks", result.cutbacks},
                     {"projected_elements", result.projected_elements},
                     {"factorizations", result.factorizations},
                     {"cg_iterations", result.linear_iterations},
                     {"linear_solver", to_string(scene.newton.linear_solver)},
                     {"linear_solver_stored_values", solver.linear_solver_storage()}};
  } else {
    ImplicitEuler solver(body, scene.conditions, scene.dynamics);
    if (contact)
      solver.set_extra_potential(contact->potential.get());
    Eigen::VectorXd x = body.rest_positions();
    if (output)
      output->write_step(0, 0.0, x);
    const auto record_frame = [&](const FrameReport& frame, const Eigen::VectorXd& state,
                                  const Eigen::VectorXd& residual) {
      record(reports::to_json(frame), frame.frame, frame.time_s, frame.load_factor, state, residual,
             true);
    };
    // Every output frame is recorded as it comes; the last one always.
    FrameReport last;
    Eigen::VectorXd last_residual;
    const DynamicResult result =
        solver.run(x, [&](const FrameReport& frame, const Eigen::VectorXd& state,
                          const Eigen::VectorXd& residual) {
          last = frame;
          if (frame.frame % scene.output.every == 0)
            record_frame(frame, state, residual);
          else
            last_residual = residual;
        });
    run.success = result.completed;
    run.failure = result.failure;
    if (last.frame > 0 && last.frame % scene.output.every != 0)
      record_frame(last, x, last_residual);
    solve_figures = {{"completed", result.completed},
                     {"reached_equilibrium", result.reached_equilibrium},
                     {"frames", result.frames},
                     {"frames_per_second", result.frames / std::max(result.wall_s, 1e-9)},
                     {"substeps", result.substeps},
                     {"cg_iterations", result.linear_iterations},
                     {"factorizations", result.factorizations},
                     {"projected_elements", result.projected_elements},
                     {"linear_solver", to_string(scene.dynamics.linear_solver)}};
  }
  if (output)
    output->finish();
  write_text_atomically(out / "reactions.csv", csv);
  summary.add_stage("solve", solve_meter, solve_figures);
  summary.results()[scene.kind == SceneKind::quasi_static ? "steps" : "frames"] = entries;
  summary.results()["success"] = run.success;
  if (!run.success)
    summary.results()["failure"] = run.failure;
  return run;
}

} // namespace ligsim::scenes
