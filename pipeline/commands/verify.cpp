#include "pipeline/commands/commands.hpp"
#include "pipeline/commands/flexion_options.hpp"
#include "pipeline/reports/verify_reports.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "common/resources.hpp"
#include "common/run_summary.hpp"
#include "common/svg_plot.hpp"
#include "sim/febio/febio_cross_check.hpp"
#include "sim/flexion/flexion_config.hpp"
#include "sim/flexion/knee_sweep.hpp"
#include "sim/verify/cube_compression.hpp"
#include "sim/verify/cube_verification.hpp"
#include "sim/verify/flexion_stability.hpp"
#include "sim/verify/stability.hpp"
#include "sim/verify/sweep.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace ligsim::cli {

namespace fs = std::filesystem;

namespace {

/// Says where verify.json went; SolverError "<n> of <m> <what> did not converge" if any did not.
void report_cube_runs(const std::vector<sim::CubeCaseResult>& results, const fs::path& out,
                      const std::string& what)
{
  const auto failed = std::count_if(results.begin(), results.end(),
                                    [](const sim::CubeCaseResult& r) { return !r.converged; });
  log_info(fmt::format("wrote {} and verify.md", (out / "verify.json").string()));
  if (failed > 0)
    fail<SolverError>("{} of {} {} did not converge (see verify.md)", failed, results.size(), what);
}

struct CubeOptions {
  fs::path reference = "data/febio-cube";
  fs::path out;
  std::vector<std::string> cases;
  int load_steps = 1;
  double residual_tolerance = 1e-8;
  std::string linear = "direct";
  bool sweep = false;
  bool compression = false;
  int cells = 0; ///< compression on an n^3 structured cube instead of the reference mesh
};

/// The paper's Tables 1 and 2 (FEBio with augmented Lagrangian unless marked), for the note.
constexpr const char* paper_tables =
    "Paper (Heimann et al. 2009), Table 1, fibers along the load, against FEBio with augmented "
    "Lagrangian:\n\n"
    "| load per node | avg fiber strain | vol. change | avg error | max error |\n"
    "| --- | ---: | ---: | ---: | ---: |\n"
    "| 0.02 N | +1.6 % | +0.2 % | 0.1 % | 0.4 % |\n"
    "| 0.05 N | +3.0 % | +0.5 % | 0.3 % | 1.0 % |\n"
    "| 0.10 N | +4.9 % | +1.1 % | 0.5 % | 1.9 % |\n"
    "| 0.20 N | +8.8 % | +2.2 % | 0.9 % | 3.4 % |\n\n"
    "Table 2 (*: against FEBio without augmented Lagrangian): fibers across tensile load 0.05 N "
    "3.9 % / 5.8 %; compressive 0.05 N 2.4 % / 5.6 %; compressive 0.10 N* 0.3 % / 0.6 %; fibers "
    "across 0.05 N* 0.4 % / 0.5 % (avg / max error).\n";

sim::NewtonSettings cube_newton(const CubeOptions& options)
{
  sim::NewtonSettings settings;
  settings.load_steps = options.load_steps;
  settings.residual_tolerance = options.residual_tolerance;
  settings.linear_solver = sim::parse_linear_solver(options.linear, "--linear");
  return settings;
}

void run_sweep(const CubeOptions& options, const sim::FebioReference& reference)
{
  if (options.cases.size() > 1)
    fail("--sweep runs one case: give at most one name in --cases");
  const std::string name = options.cases.empty() ? "par_t020_pen" : options.cases.front();
  const sim::FebioCase* chosen = nullptr;
  for (const sim::FebioCase& c : reference.cases)
    if (c.name == name)
      chosen = &c;
  if (!chosen)
    fail("--cases: no case named '{}' in {}", name, (options.reference / "cases.json").string());
  RunSummary summary("verify cube --sweep");
  summary.inputs()["reference"] = options.reference.string();
  summary.parameters()["case"] = name;
  const sim::SweepSettings settings;
  StageMeter meter;
  const std::vector<sim::SweepRow> rows =
      sim::run_sweep(reference, *chosen, settings, [](const sim::SweepRow& r) {
        log_info(r.converged
                     ? fmt::format("{} n={} {} tol {:g}: avg error vs finest {:.2e} %, {:.2f} s",
                                   r.family, r.cells, r.linear_solver, r.tolerance,
                                   r.avg_error_finest_pct, r.wall_s)
                     : fmt::format("{} n={} {} tol {:g}: failed: {}", r.family, r.cells,
                                   r.linear_solver, r.tolerance, r.failure));
      });
  summary.add_stage("sweep", meter, {{"runs", rows.size()}});
  ensure_directory(options.out);
  write_text_atomically(options.out / "sweep.csv", sim::sweep_csv(rows));
  write_text_atomically(options.out / "sweep.svg", svg_line_plot(sim::sweep_plot(rows, name)));
  write_text_atomically(
      options.out / "sweep.md",
      fmt::format("# Error against run time, case {} (matched energy)\n\nErrors: top-face node "
                  "positions in percent of the edge, against the finest mesh ({}^3 hexes, "
                  "interpolated at each mesh's nodes) and against FEBio on its own 16^3 mesh. "
                  "'vs continuum': average top-face displacement against FEBio's quadratic-tet "
                  "solution (continuum.json).\n\n",
                  name, settings.finest_cells) +
          sim::sweep_table(rows));
  summary.results()["rows"] = rows.size();
  summary.write(options.out);
  log_info(fmt::format("wrote {}, sweep.svg and sweep.md", (options.out / "sweep.csv").string()));
}

/// The compression cases, checked by equilibrium (no FEBio solution of them here).
void run_compression(const CubeOptions& options, const sim::FebioReference& reference)
{
  RunSummary summary("verify cube --compression");
  summary.inputs()["reference"] = options.reference.string();
  summary.parameters()["load_steps"] = options.load_steps;
  summary.parameters()["residual_tolerance"] = options.residual_tolerance;
  summary.parameters()["cells"] = options.cells;
  const std::vector<sim::FebioCase> cases = sim::cube_compression_cases(reference);
  const std::set<std::string> wanted(options.cases.begin(), options.cases.end());
  for (const std::string& name : wanted) {
    bool known = false;
    for (const sim::FebioCase& c : cases)
      known = known || c.name == name;
    if (!known)
      fail("--cases: no compression case named '{}' (cmp_along_010_lnj, cmp_across_020_jm1, ...)",
           name);
  }
  StageMeter read_meter;
  const sim::FebioMesh mesh = options.cells > 0
                                  ? sim::structured_cube(options.cells, reference.edge_mm)
                                  : sim::read_febio_mesh(reference.mesh_file);
  summary.add_stage("read", read_meter,
                    {{"nodes", mesh.mesh.V.rows()}, {"elements", mesh.mesh.T.rows()}});
  // On another mesh the total load (the stress) stays the reference mesh's.
  const double load_scale =
      options.cells > 0 ? 289.0 / static_cast<double>(mesh.top_nodes.size()) : 1.0;
  const sim::NewtonSettings settings = cube_newton(options);
  std::vector<sim::CubeCaseResult> results;
  StageMeter solve_meter;
  for (sim::FebioCase c : cases) {
    if (!wanted.empty() && wanted.count(c.name) == 0)
      continue;
    c.force_per_top_node_n *= load_scale;
    results.push_back(sim::run_cube_case(mesh, c, sim::CubeEnergy::matched, settings, Points(),
                                         reference.edge_mm));
    const sim::CubeCaseResult& r = results.back();
    log_info(r.converged
                 ? fmt::format("{}: relative residual {:.1e}, reactions balance to {:.1e}, "
                               "{} Newton iterations in {} sub-steps, {:.2f} s{}{}",
                               r.name, r.relative_residual, r.balance_error, r.newton_iterations,
                               r.substeps, r.wall_s,
                               r.converged_at_floor ? "; at the round-off floor: " + r.floor
                                                    : std::string(),
                               r.negative_eigenvalues > 0 ? "; " + r.instability : std::string())
                 : fmt::format("{}: failed: {}", r.name, r.failure));
  }
  summary.add_stage("solve", solve_meter, {{"runs", results.size()}});
  ensure_directory(options.out);
  const nlohmann::json json = reports::to_json(results);
  write_text_atomically(options.out / "verify.json", json.dump(2) + "\n");
  write_text_atomically(options.out / "verify.md",
                        fmt::format("# Cube compression, checked by equilibrium\n\n{} tets, "
                                    "FEBio's penalty energy (fiber convention weiss), bottom "
                                    "fixed, the load on every top node pushing down. Relative "
                                    "residual: free-DOF residual / load; reaction balance: |bottom "
                                    "reactions + load| / load.\n\n",
                                    mesh.mesh.T.rows()) +
                            sim::cube_equilibrium_table(results));
  summary.results() = json;
  summary.write(options.out);
  report_cube_runs(results, options.out, "compression runs");
}

void run_cube(const CubeOptions& options)
{
  if (!fs::is_directory(options.reference))
    fail("reference folder {} not found (pass --reference DIR)", options.reference.string());
  RunSummary summary("verify cube");
  summary.inputs()["reference"] = options.reference.string();
  summary.parameters()["load_steps"] = options.load_steps;
  summary.parameters()["residual_tolerance"] = options.residual_tolerance;
  summary.parameters()["linear_solver"] = options.linear;

  if (options.compression) {
    run_compression(options, sim::read_febio_reference(options.reference));
    return;
  }
  StageMeter read_meter;
  const sim::FebioReference reference = sim::read_febio_reference(options.reference);
  const sim::FebioMesh mesh = sim::read_febio_mesh(reference.mesh_file);
  const std::set<std::string> wanted(options.cases.begin(), options.cases.end());
  for (const std::string& name : wanted) {
    bool known = false;
    for (const sim::FebioCase& c : reference.cases)
      known = known || c.name == name;
    if (!known)
      fail("--cases: no case named '{}' in {}", name, (options.reference / "cases.json").string());
  }
  summary.add_stage("read", read_meter,
                    {{"nodes", mesh.mesh.V.rows()}, {"elements", mesh.mesh.T.rows()}});
  if (options.sweep) {
    run_sweep(options, reference);
    return;
  }

  const sim::NewtonSettings settings = cube_newton(options);
  std::vector<sim::CubeCaseResult> results;
  StageMeter solve_meter;
  for (const sim::FebioCase& c : reference.cases) {
    if (!wanted.empty() && wanted.count(c.name) == 0)
      continue;
    const Points febio = sim::read_febio_displacements(c.displacements, mesh.mesh.V.rows());
    for (sim::CubeEnergy energy : {sim::CubeEnergy::matched, sim::CubeEnergy::paper}) {
      results.push_back(sim::run_cube_case(mesh, c, energy, settings, febio, reference.edge_mm));
      const sim::CubeCaseResult& r = results.back();
      log_info(r.converged
                   ? fmt::format("{} ({}): avg error {:.2e} %, max {:.2e} % of the edge, "
                                 "{} Newton iterations, {} factorisations, {:.2f} s "
                                 "({:.2f} s CPU; FEBio {:.1f} s)",
                                 r.name, to_string(energy), r.avg_error_pct, r.max_error_pct,
                                 r.newton_iterations, r.factorizations, r.wall_s, r.cpu_s,
                                 r.febio_wall_s)
                   : fmt::format("{} ({}): failed: {}", r.name, to_string(energy), r.failure));
    }
  }
  summary.add_stage("solve", solve_meter, {{"runs", results.size()}});

  ensure_directory(options.out);
  const nlohmann::json json = reports::to_json(results);
  write_text_atomically(options.out / "verify.json", json.dump(2) + "\n");
  const std::string table = "# Cube verification against FEBio 4.11\n\n"
                            "Errors in percent of the cube edge (1 mm): top face nodes, then all "
                            "nodes. Wall time: set-up and static solve of one case.\n\n" +
                            sim::cube_results_table(results) + "\n" + paper_tables;
  write_text_atomically(options.out / "verify.md", table);
  summary.results() = json;
  summary.write(options.out);
  report_cube_runs(results, options.out, "cube runs");
}

struct StabilityOptions {
  fs::path out;
  int cells = 8;
  std::vector<std::string> cases;
  std::string suite = "cube";
  fs::path model;
  fs::path fine_model;
  fs::path config = "data/vhf-right-knee/flexion.toml";
  std::vector<double> angles;
};

/// `--suite flexion`: the knee model's extreme cases (sim/verify/flexion_stability).
/// SolverError "<count> <what> (see stability.md)" when any of `results` failed.
template <class Result>
void fail_on_failed_cases(const std::vector<Result>& results, const std::string& what)
{
  const auto failed = std::count_if(results.begin(), results.end(), [](const Result& r) {
    return r.outcome == sim::Outcome::failed;
  });
  if (failed > 0)
    fail<SolverError>("{} {} (see stability.md)", failed, what);
}

void run_flexion_stability(const StabilityOptions& options)
{
  RunSummary summary("verify stability --suite flexion");
  if (options.model.empty())
    fail("verify stability --suite flexion: pass --model DIR, a model built by `ligsim build` "
         "(the coarse one; --fine-model DIR for the fine cases)");
  sim::FlexionSettings base;
  sim::read_flexion_config(options.config, base);
  summary.inputs()["model"] = options.model.string();
  summary.inputs()["fine_model"] = options.fine_model.string();
  summary.inputs()["config"] = options.config.string();
  sim::FlexionStabilitySuite suite =
      options.angles.empty()
          ? sim::FlexionStabilitySuite(base, options.model, options.fine_model)
          : sim::FlexionStabilitySuite(base, options.model, options.fine_model, options.angles);
  summary.parameters()["static_angles_deg"] = suite.static_angles_deg();
  std::vector<std::string> names = options.cases;
  if (names.empty())
    for (const sim::StabilityCase& c : sim::FlexionStabilitySuite::cases())
      names.push_back(c.name);
  ensure_directory(options.out);
  std::vector<sim::FlexionCaseResult> results;
  StageMeter meter;
  Progress progress("flexion stability cases", names.size());
  for (const std::string& name : names) {
    results.push_back(suite.run(name, options.out));
    const sim::FlexionCaseResult& r = results.back();
    log_info(fmt::format("{}: {} ({} iterations, {:.1f} s, max fiber strain {:.1f} %){}", r.name,
                         to_string(r.outcome), r.iterations, r.wall_s, 100.0 * r.max_fiber_strain,
                         r.diagnostic.empty() ? "" : ": " + r.diagnostic));
    progress.advance();
  }
  progress.finish();
  summary.add_stage("cases", meter, {{"cases", results.size()}});
  const nlohmann::json json = reports::to_json(results);
  write_text_atomically(options.out / "stability.json", json.dump(2) + "\n");
  write_text_atomically(options.out / "stability.csv", sim::flexion_stability_csv(results));
  write_text_atomically(
      options.out / "stability.md",
      fmt::format("# Stability of the knee flexion\n\nModel {} (fine: {}), flexion config {}; "
                  "contact off except in contact_140. Files of each case in its folder.\n\n",
                  options.model.string(),
                  options.fine_model.empty() ? "none" : options.fine_model.string(),
                  options.config.string()) +
          sim::flexion_stability_table(results));
  summary.results() = json;
  summary.write(options.out);
  fail_on_failed_cases(results, "flexion stability cases ended without an answer or a "
                                "diagnostic, or wrote a non-finite value");
}

void run_stability(const StabilityOptions& options)
{
  if (options.suite == "flexion") {
    run_flexion_stability(options);
    return;
  }
  RunSummary summary("verify stability");
  summary.parameters()["cells"] = options.cells;
  std::vector<std::string> names = options.cases;
  if (names.empty())
    for (const sim::StabilityCase& c : sim::stability_cases())
      names.push_back(c.name);
  std::vector<sim::StabilityResult> results;
  StageMeter meter;
  for (const std::string& name : names) {
    results.push_back(sim::run_stability_case(name, options.cells));
    const sim::StabilityResult& r = results.back();
    log_info(fmt::format("{}: {} ({} iterations, {:.2f} s, worst J {:.4f}){}", r.name,
                         to_string(r.outcome), r.iterations, r.wall_s, r.min_j,
                         r.diagnostic.empty() ? "" : ": " + r.diagnostic));
  }
  summary.add_stage("cases", meter, {{"cases", results.size()}});
  ensure_directory(options.out);
  const nlohmann::json json = reports::to_json(results);
  write_text_atomically(options.out / "stability.json", json.dump(2) + "\n");
  write_text_atomically(options.out / "stability.md",
                        fmt::format("# Stability on stiff and extreme cases\n\nUnit cube, {0} x "
                                    "{0} x {0} hexes x 5 tets, MCL material (paper convention, "
                                    "K/2 (J-1)^2), bottom fixed, load on the top face.\n\n",
                                    options.cells) +
                            sim::stability_table(results));
  summary.results() = json;
  summary.write(options.out);
  fail_on_failed_cases(results, "stability cases ended without an answer or a diagnostic");
}

struct FebioOptions {
  FlexionOptions flexion;
  fs::path febio;
  fs::path out;
  /// ligsim's barrier activation distance for the comparison, mm: FEBio's contact keeps no gap,
  /// so ours is made to keep a negligible one (docs/knee.md measures the effect).
  double d_hat_mm = 0.01;
  sim::FebContactSettings febio_contact;
};

/// `verify febio`: the flexion by ligsim and by FEBio on the same settings, side by side.
void run_verify_febio(const FebioOptions& options)
{
  RunSummary summary("verify febio");
  const auto start = std::chrono::steady_clock::now();
  sim::FlexionSettings settings = flexion_settings_from(options.flexion, "verify febio");
  const sim::KneeModel model = sim::load_ligament_as_flexed(settings, "verify febio");
  settings.images = false;
  if (settings.material.fiber->convention == sim::FiberConvention::paper) {
    settings.material.fiber->convention = sim::FiberConvention::weiss;
    log_info("fiber convention: 'weiss' in both solvers for the comparison (FEBio implements only "
             "Weiss' convention; the config's 'paper' is replaced)");
  }
  const bool contact = settings.contact.enabled.value_or(true);
  if (contact && settings.contact.barrier.d_hat_mm != options.d_hat_mm) {
    log_info(fmt::format("contact: d_hat {} mm in ligsim for the comparison (the config's {} mm "
                         "keeps a gap that FEBio's contact does not have; --d-hat sets it)",
                         options.d_hat_mm, settings.contact.barrier.d_hat_mm));
    settings.contact.barrier.d_hat_mm = options.d_hat_mm;
  }
  summary.inputs()["model"] = settings.model_dir.string();
  summary.inputs()["config"] = options.flexion.config.string();
  summary.inputs()["febio"] = options.febio.string();
  const sim::KneeMotion motion = sim::resolve_knee_motion(model, settings);
  const sim::ResolvedAxis& axis = motion.axis;
  const double setup_s = seconds_since(start);
  summary.parameters() = {{"angles_deg", motion.angles_deg},
                          {"convention", to_string(settings.material.fiber->convention)},
                          {"volumetric", to_string(settings.material.volumetric)},
                          {"in_situ_strain", settings.in_situ_strain},
                          {"contact", contact},
                          {"d_hat_mm", settings.contact.barrier.d_hat_mm},
                          {"febio_penalty", options.febio_contact.penalty},
                          {"axis_point_mm", json_vector3(axis.axis.point_mm)},
                          {"axis_direction", json_vector3(axis.axis.direction)}};
  ensure_directory(options.out);
  StageMeter meter;
  const sim::CrossCheck check = sim::cross_check_with_febio(
      model, settings, motion, options.febio, options.out, setup_s, options.febio_contact);
  summary.add_stage("cross_check", meter,
                    {{"ours_wall_s", check.ours_wall_s}, {"febio_wall_s", check.run.wall_s}});
  for (const std::string& warning : check.warnings)
    log_info("warning: " + warning);
  write_text_atomically(options.out / "febio_comparison.csv", sim::comparison_csv(check.rows));
  const std::string table = sim::comparison_table(check.rows);
  write_text_atomically(options.out / "febio_comparison.md",
                        fmt::format("# ligsim against FEBio on {}\n\nFEBio's energy and fiber "
                                    "stretch: its node positions measured by ligsim's law.\n\n",
                                    settings.model_dir.string()) +
                            table);
  nlohmann::json steps = nlohmann::json::array();
  for (std::size_t k = 0; k < check.febio.size(); ++k) {
    const sim::FebioStep& f = check.febio[k];
    nlohmann::json bones = nlohmann::json::object();
    for (const sim::BoneContact& bone : check.ours[k].contact)
      bones[bone.bone] = {{"ours_contact_force_n", json_vector3(bone.force_n)},
                          {"ours_min_gap_mm", bone.min_gap_mm},
                          {"ours_penetration_mm", bone.penetration_mm}};
    for (const sim::BoneContact& bone : check.febio_contact[k])
      bones[bone.bone]["febio_penetration_mm"] = bone.penetration_mm;
    steps.push_back({{"angle_deg", f.angle_deg},
                     {"febio_femur_force_n", json_vector3(f.femur_force_n)},
                     {"ours_femur_attachment_force_n", json_vector3(check.ours[k].femur_force_n)},
                     {"febio_logged_energy_mj", f.logged_energy_mj},
                     {"febio_femur_pose_error_mm", f.femur_pose_error_mm},
                     {"bones", bones}});
  }
  summary.results() = {{"steps", steps},
                       {"febio_log", check.run.log.string()},
                       {"ours_wall_s", check.ours_wall_s},
                       {"febio_wall_s", check.run.wall_s}};
  summary.write(options.out);
  fmt::print("{}", table);
  log_info(fmt::format("table: {}", (options.out / "febio_comparison.csv").string()));
}

} // namespace

void add_verify_command(CLI::App& app)
{
  auto* verify = app.add_subcommand("verify", "verification against FEBio and stability report");
  verify->require_subcommand(1);

  auto options = std::make_shared<CubeOptions>();
  auto* cube = verify->add_subcommand(
      "cube", "the paper's cube experiments against FEBio (verify.json, verify.md)");
  cube->add_option("--reference", options->reference,
                   "folder with cases.json, mesh.txt and FEBio's displacements")
      ->capture_default_str();
  cube->add_option("--out", options->out, "output folder")->required();
  cube->add_option("--cases", options->cases, "only these cases (names from cases.json)")
      ->delimiter(',');
  cube->add_option("--steps", options->load_steps, "load steps")->capture_default_str();
  cube->add_option("--tolerance", options->residual_tolerance, "relative residual to converge to")
      ->capture_default_str();
  cube->add_option("--linear", options->linear, "linear solver: direct or pcg")
      ->capture_default_str();
  cube->add_flag("--sweep", options->sweep,
                 "error against run time over mesh sizes, tolerances and linear solvers");
  cube->add_flag("--compression", options->compression,
                 "compression cases 0.02-0.20 N per node along and across the fibers, checked "
                 "by equilibrium");
  cube->add_option("--cells", options->cells,
                   "with --compression: an n^3 structured cube instead of the reference mesh, "
                   "with the reference's total load (289 top nodes)");
  cube->callback([options] { run_cube(*options); });

  auto stability_options = std::make_shared<StabilityOptions>();
  auto* stability = verify->add_subcommand(
      "stability", "stiff and extreme cases: converged or a diagnostic (stability.json, .md)");
  stability->add_option("--out", stability_options->out, "output folder")->required();
  stability->add_option("--cells", stability_options->cells, "hexes per cube edge")
      ->capture_default_str();
  stability->add_option("--cases", stability_options->cases, "only these cases")->delimiter(',');
  stability
      ->add_option("--suite", stability_options->suite,
                   "cube (default: the unit cube's stiff cases) or flexion (the knee model)")
      ->check(CLI::IsMember({"cube", "flexion"}));
  stability->add_option("--model", stability_options->model,
                        "flexion: the coarse model folder (output of `ligsim build`)");
  stability->add_option("--fine-model", stability_options->fine_model,
                        "flexion: the fine model folder (its cases are skipped without it)");
  stability
      ->add_option("--config", stability_options->config,
                   "flexion: the flexion config giving axis, material and solver")
      ->capture_default_str();
  stability
      ->add_option("--angles", stability_options->angles,
                   "flexion: the quasi-static angles, deg (default 0,20,...,140)")
      ->delimiter(',');
  stability->callback([stability_options] { run_stability(*stability_options); });

  auto febio_options = std::make_shared<FebioOptions>();
  auto* febio = verify->add_subcommand(
      "febio", "the knee flexion by ligsim and by FEBio on the same settings "
               "(febio_comparison.csv, knee.feb and FEBio's knee.log)");
  add_flexion_options(*febio, febio_options->flexion, false);
  febio->add_option("--febio", febio_options->febio, "FEBio 4's solver executable (febio4)")
      ->required();
  febio->add_option("--out", febio_options->out, "output folder")->required();
  febio
      ->add_option("--d-hat", febio_options->d_hat_mm,
                   "contact on: ligsim's barrier activation distance for the comparison, mm "
                   "(FEBio's contact keeps no gap)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  febio
      ->add_option("--febio-penalty", febio_options->febio_contact.penalty,
                   "contact on: scale of FEBio's automatic contact penalty")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  febio->callback([febio_options] { run_verify_febio(*febio_options); });
}

} // namespace ligsim::cli
