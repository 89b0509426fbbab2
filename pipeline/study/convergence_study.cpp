#include "pipeline/study/convergence_study.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "pipeline/stage_graph/stage_files.hpp"
#include "pipeline/study/csv_text.hpp"
#include "pipeline/study/run_errors.hpp"
#include "pipeline/study/study_plot.hpp"
#include "pipeline/study/study_runs.hpp"
#include "stages/geometry/surface_topology.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

namespace ligsim::study {

namespace fs = std::filesystem;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
/// The paper's interactive rate (sec. 5.2: 15 frames per second for 5,911 tets).
constexpr double kPaperFramesPerSecond = 15.0;

/// The femur force error under which a run counts as converged (the 1 %).
constexpr double kConvergedForceError = 0.01;

struct RunSpec {
  std::string family;
  double mesh_scale = 1.0;
  double voxel_scale = 1.0;
  double time_step_s = 0.0; ///< 0: quasi-static
  int order = 0;            ///< 0: the config's own
};

/// One ligament in one run of the ladders.
struct Run {
  RunSpec spec;
  std::string ligament;
  BuiltLigament build;
  FlexionFigures flexion;
  std::string failure; ///< empty when the run reached every angle
  QuantityValues worst_vs_reference{};
  QuantityValues worst_vs_family{};
  double energy_error_vs_extrapolated = kNaN;
  std::vector<AngleErrors> errors;
};

std::string model_name(double mesh_scale, double voxel_scale, int order)
{
  const std::string name = fmt::format("mesh{:g}-voxel{:g}", mesh_scale, voxel_scale);
  return order > 0 ? fmt::format("{}-order{}", name, order) : name;
}

/// The mesh ladder's family of an element order.
std::string mesh_family(int order)
{
  if (order == 1)
    return "quasi-static, mesh, linear tets";
  if (order == 2)
    return "quasi-static, mesh, 10-node tets";
  return "quasi-static, mesh";
}

bool is_mesh_family(const std::string& family)
{
  return family.rfind("quasi-static, mesh", 0) == 0;
}

/// The config's sizes times the scales; a size the config leaves at 0 starts from the linear
/// build's default (mesh h/2, facet distance h/20, voxel h/8), for 10-node tets too, so that the
/// two orders' ladders share their sizes (a 10-node build's own default is 1.7 h).
pipeline::BuildConfig scaled_config(const pipeline::BuildConfig& base, double thickness_mm,
                                    double mesh_scale, double voxel_scale, int order)
{
  auto scaled = [](double value, double fallback, double scale) {
    return scale * (value > 0.0 ? value : fallback);
  };
  pipeline::BuildConfig config = base;
  config.tetmesh.cell_size_mm = scaled(base.tetmesh.cell_size_mm, thickness_mm / 2.0, mesh_scale);
  config.tetmesh.facet_size_mm = scaled(base.tetmesh.facet_size_mm, thickness_mm / 2.0, mesh_scale);
  config.tetmesh.facet_distance_mm =
      scaled(base.tetmesh.facet_distance_mm, thickness_mm / 20.0, mesh_scale);
  config.voxelize.spacing_mm = scaled(base.voxelize.spacing_mm, thickness_mm / 8.0, voxel_scale);
  if (order > 0)
    config.tetmesh.order = order;
  return config;
}

/// Every ligament's sizes scaled from its own (`thickness_mm` per ligament).
StudyModel scaled_model(const StudyModel& base, const std::vector<double>& thickness_mm,
                        const RunSpec& spec)
{
  StudyModel model = base;
  for (std::size_t l = 0; l < model.config.ligaments.size(); ++l)
    model.config.ligaments[l].build = scaled_config(base.config.ligaments[l].build, thickness_mm[l],
                                                    spec.mesh_scale, spec.voxel_scale, spec.order);
  return model;
}

/// Seconds of solve per displayed frame: an implicit Euler frame, or one angle's equilibrium.
double seconds_per_frame(const Run& run)
{
  if (run.flexion.frames_per_second > 0.0)
    return 1.0 / run.flexion.frames_per_second;
  return run.flexion.frames > 0 ? run.flexion.solve_s / run.flexion.frames : kNaN;
}

std::string percent(double fraction)
{
  return std::isfinite(fraction) ? fmt::format("{:.3g} %", 100.0 * fraction) : "";
}

/// Energy at each angle extrapolated from the three finest meshes where monotone.
std::map<double, double> extrapolated_energy(const std::vector<const Run*>& mesh_runs,
                                             nlohmann::json& report)
{
  std::map<double, double> energies;
  if (mesh_runs.size() < 3)
    return energies;
  const std::size_t n = mesh_runs.size();
  const std::array<const Run*, 3> finest = {mesh_runs[n - 3], mesh_runs[n - 2], mesh_runs[n - 1]};
  std::array<double, 3> h{};
  for (std::size_t i = 0; i < 3; ++i)
    h[i] = std::cbrt(1.0 / std::max(finest[i]->flexion.tets, 1)); // tet size up to a constant
  nlohmann::json orders = nlohmann::json::array();
  for (const AngleFigures& angle : finest[2]->flexion.angles) {
    std::array<double, 3> f{};
    bool all = true;
    for (std::size_t i = 0; i < 3; ++i) {
      const auto& angles = finest[i]->flexion.angles;
      const auto match = std::find_if(angles.begin(), angles.end(), [&](const AngleFigures& a) {
        return std::abs(a.angle_deg - angle.angle_deg) < 1e-9;
      });
      all = all && match != angles.end();
      if (match != angles.end())
        f[i] = match->strain_energy_mj;
    }
    const std::optional<Extrapolation> e = all ? richardson(h, f) : std::nullopt;
    nlohmann::json entry = {{"angle_deg", angle.angle_deg}, {"monotone", e.has_value()}};
    if (e) {
      energies[angle.angle_deg] = e->value;
      entry.update({{"energy_mj", e->value},
                    {"order", e->order},
                    {"finest_error_pct", 100.0 * std::abs(f[2] - e->value) / std::abs(e->value)}});
    }
    orders.push_back(entry);
  }
  report["richardson_energy"] = orders;
  return energies;
}

/// The quasi-static mesh run, other than the reference, whose femur force lies within 1 % of
/// the reference's at every angle in the least solve time; null when none does.
nlohmann::json fastest_converged(const std::vector<Run>& runs, const std::string& reference_family,
                                 double finest_mesh)
{
  const Run* best = nullptr;
  for (const Run& run : runs) {
    const bool reference =
        run.spec.family == reference_family && run.spec.mesh_scale == finest_mesh;
    if (reference || !run.failure.empty() || !is_mesh_family(run.spec.family) ||
        !(run.worst_vs_reference[3] <= kConvergedForceError))
      continue;
    if (!best || run.flexion.solve_s < best->flexion.solve_s)
      best = &run;
  }
  if (!best)
    return nullptr;
  return {{"family", best->spec.family},
          {"mesh_scale", best->spec.mesh_scale},
          {"tets", best->flexion.tets},
          {"solve_s", best->flexion.solve_s},
          {"femur_force_error", best->worst_vs_reference[3]}};
}

/// The table rows of every ligament's runs, a ligament after the other, and each ligament's
/// fastest run within 1 % (`ligaments`: the report's entries).
void write_tables(const std::vector<std::vector<Run>>& runs, const fs::path& out,
                  const std::string& reference, const nlohmann::json& ligaments)
{
  std::string csv = "ligament,family,mesh_scale,voxel_scale,mode,time_step_s,tets,build_s,"
                    "build_peak_mib,solve_s,solve_peak_mib,frames,s_per_frame,frames_per_second,"
                    "energy_error,mean_strain_error,p95_strain_error,femur_force_error,"
                    "regional_strain_error,energy_error_vs_family,mean_strain_error_vs_family,"
                    "p95_strain_error_vs_family,femur_force_error_vs_family,"
                    "regional_strain_error_vs_family,energy_error_vs_extrapolated,failure\n";
  std::string angles_csv = "ligament,family,mesh_scale,voxel_scale,time_step_s,tets,angle_deg,"
                           "strain_energy_mj,mean_fiber_stretch,p95_fiber_stretch,"
                           "max_fiber_stretch,femur_force_n,energy_error,mean_strain_error,"
                           "p95_strain_error,femur_force_error,regional_fiber_stretch,"
                           "regional_strain_error\n";
  std::string md = fmt::format(
      "Errors: the largest over the angles, relative to the reference ({}); fiber errors "
      "compare strains (stretch - 1), the force compares vectors. Time per frame: one implicit "
      "Euler frame, or one angle's equilibrium (quasi-static). The paper: 15 frames per second "
      "(0.067 s per frame) for 5,911 tets. No contact (the ligament may pass through the "
      "bones).\n\n"
      "| ligament | family | tets | voxel scale | dt s | build s | solve s | s per frame | peak "
      "MiB | energy | mean strain | p95 strain | femur force | regional peak | energy vs "
      "Richardson |\n"
      "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | "
      "---: | ---: |\n",
      reference);
  for (const std::vector<Run>& ligament_runs : runs)
    for (const Run& run : ligament_runs) {
      const bool interactive = run.spec.time_step_s > 0.0;
      const auto& r = run.worst_vs_reference;
      const auto& f = run.worst_vs_family;
      csv += fmt::format(
          "{},{},{},{},{},{},{},{:.3f},{:.1f},{:.3f},{:.1f},{},{:.5g},{:.4g},{:.6g},{:.6g},{:.6g},"
          "{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{}\n",
          csv_quoted(run.ligament), csv_quoted(run.spec.family), run.spec.mesh_scale,
          run.spec.voxel_scale, interactive ? "interactive" : "static", run.spec.time_step_s,
          run.flexion.tets, run.build.build_s, run.build.peak_rss_mib, run.flexion.solve_s,
          run.flexion.peak_rss_mib, run.flexion.frames, seconds_per_frame(run),
          run.flexion.frames_per_second, r[0], r[1], r[2], r[3], r[4], f[0], f[1], f[2], f[3], f[4],
          run.energy_error_vs_extrapolated, csv_quoted(run.failure));
      for (const AngleFigures& a : run.flexion.angles) {
        QuantityValues e;
        e.fill(kNaN);
        for (const AngleErrors& row : run.errors)
          if (std::abs(row.angle_deg - a.angle_deg) < 1e-9)
            e = row.error;
        angles_csv += fmt::format(
            "{},{},{},{},{},{},{},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},"
            "{:.6g},{:.6g},{:.6g},{:.6g}\n",
            csv_quoted(run.ligament), csv_quoted(run.spec.family), run.spec.mesh_scale,
            run.spec.voxel_scale, run.spec.time_step_s, run.flexion.tets, a.angle_deg,
            a.strain_energy_mj, a.mean_fiber_stretch, a.p95_fiber_stretch, a.max_fiber_stretch,
            a.femur_force_n.norm(), e[0], e[1], e[2], e[3], a.regional_fiber_stretch, e[4]);
      }
      md += fmt::format(
          "| {} | {} | {} | {:g} | {} | {:.2f} | {:.2f} | {:.4f} | {:.0f} | {} | {} | {} | "
          "{} | {} | {} |\n",
          run.ligament, run.spec.family + (run.failure.empty() ? "" : " (failed)"),
          run.flexion.tets, run.spec.voxel_scale,
          interactive ? fmt::format("{:g}", run.spec.time_step_s) : "", run.build.build_s,
          run.flexion.solve_s, seconds_per_frame(run),
          std::max(run.build.peak_rss_mib, run.flexion.peak_rss_mib), percent(r[0]), percent(r[1]),
          percent(r[2]), percent(r[3]), percent(r[4]), percent(run.energy_error_vs_extrapolated));
    }
  md += fmt::format("\nWithin {:g} % of the reference's femur force at every angle, in the least "
                    "solve time:\n\n",
                    100.0 * kConvergedForceError);
  for (const nlohmann::json& ligament : ligaments) {
    const nlohmann::json& best = ligament["fastest_within_1pct_femur_force"];
    md += fmt::format("- {}: {}\n", ligament["ligament"].get<std::string>(),
                      best.is_null()
                          ? std::string("none of the runs but the reference")
                          : fmt::format("{}, mesh x{:g} ({} tets, {:.2f} s; {})",
                                        best["family"].get<std::string>(),
                                        best["mesh_scale"].get<double>(), best["tets"].get<int>(),
                                        best["solve_s"].get<double>(),
                                        percent(best["femur_force_error"].get<double>())));
  }
  write_text_atomically(out / "convergence.csv", csv);
  write_text_atomically(out / "convergence_angles.csv", angles_csv);
  write_text_atomically(out / "convergence.md", md);
}

/// The error of `quantity` against run time, one curve per family (per ligament and family in a
/// knee), into `<stem>.svg` / `.png`.
void write_convergence_plot(const std::vector<std::vector<Run>>& runs, Quantity quantity,
                            const std::string& what, const fs::path& stem, bool png)
{
  PlotSpec spec;
  spec.title = "Knee flexion: " + what + " error against run time";
  spec.x_label = "solve time per frame (s)";
  spec.y_label = "largest " + what + " error over the angles (%)";
  spec.log_x = true;
  spec.log_y = true;
  std::map<std::string, PlotSeries> families;
  std::vector<std::string> order;
  double low = INFINITY, high = 0.0;
  for (const std::vector<Run>& ligament_runs : runs)
    for (const Run& run : ligament_runs) {
      if (!run.failure.empty())
        continue;
      const std::string name =
          runs.size() > 1 ? run.ligament + ": " + run.spec.family : run.spec.family;
      if (!families.count(name))
        order.push_back(name);
      PlotSeries& series = families[name];
      series.name = name;
      const double error = 100.0 * run.worst_vs_reference[static_cast<std::size_t>(quantity)];
      series.x.push_back(seconds_per_frame(run));
      series.y.push_back(error);
      series.point_labels.push_back(fmt::format("{}", run.flexion.tets));
      if (std::isfinite(error) && error > 0.0) {
        low = std::min(low, error);
        high = std::max(high, error);
      }
    }
  for (const std::string& name : order) {
    PlotSeries& s = families[name];
    // Sorted by time, so that a curve runs left to right.
    std::vector<std::size_t> idx(s.x.size());
    for (std::size_t i = 0; i < idx.size(); ++i)
      idx[i] = i;
    std::sort(idx.begin(), idx.end(),
              [&](std::size_t a, std::size_t b) { return s.x[a] < s.x[b]; });
    PlotSeries sorted;
    sorted.name = s.name;
    for (std::size_t i : idx) {
      sorted.x.push_back(s.x[i]);
      sorted.y.push_back(s.y[i]);
      sorted.point_labels.push_back(s.point_labels[i]);
    }
    spec.series.push_back(sorted);
  }
  if (std::isfinite(low)) {
    PlotSeries paper;
    paper.name = "paper: 15 frames per second (0.067 s per frame)";
    paper.x = {1.0 / kPaperFramesPerSecond, 1.0 / kPaperFramesPerSecond};
    paper.y = {low / 2.0, high * 2.0};
    spec.series.push_back(paper);
  }
  write_plot(spec, stem, png);
}

/// The errors of one ligament's runs: against the reference, its family's reference and the
/// extrapolation. `sweeps` holds every sweep by key, every ligament's figures.
void compare_runs(std::vector<Run>& runs, const std::string& ligament,
                  const std::map<std::string, std::vector<FlexionFigures>>& sweeps,
                  const FlexionFigures& reference, const std::string& reference_family,
                  const std::string& finest_voxel_key, nlohmann::json& report)
{
  std::vector<const Run*> mesh_runs;
  for (const Run& run : runs)
    if (run.spec.family == reference_family && run.failure.empty())
      mesh_runs.push_back(&run);
  const std::map<double, double> extrapolated = extrapolated_energy(mesh_runs, report);
  const auto sweep_of = [&](const std::string& key) -> const FlexionFigures* {
    const auto found = sweeps.find(key);
    return found != sweeps.end() ? figures_of(found->second, ligament) : nullptr;
  };

  for (Run& run : runs) {
    run.errors = angle_errors(run.flexion, reference);
    run.worst_vs_reference = worst_errors(run.errors);
    // The family's own reference isolates its parameter: the finest voxel at the same mesh, the
    // quasi-static run on the same mesh for the interactive runs.
    const FlexionFigures* family = &reference;
    if (run.spec.family == "quasi-static, voxel")
      family = sweep_of(finest_voxel_key);
    else if (run.spec.time_step_s > 0.0)
      family = sweep_of(model_name(run.spec.mesh_scale, 1.0, run.spec.order) + "-0");
    run.worst_vs_family.fill(kNaN);
    if (family)
      run.worst_vs_family = worst_errors(angle_errors(run.flexion, *family));
    if (!extrapolated.empty() && run.failure.empty()) {
      double worst = 0.0;
      for (const AngleFigures& a : run.flexion.angles)
        if (const auto e = extrapolated.find(a.angle_deg); e != extrapolated.end())
          worst = std::max(worst, std::abs(a.strain_energy_mj - e->second) / std::abs(e->second));
      run.energy_error_vs_extrapolated = worst;
    }
  }
}

} // namespace

double ligament_thickness_mm(const pipeline::BuildConfig& config)
{
  const TriangleSurface surface = pipeline::load_ligament(config);
  return 2.0 * std::abs(signed_volume(surface)) / surface_area(surface);
}

nlohmann::json run_convergence_study(const ConvergenceInputs& inputs)
{
  const ConvergenceLadder& ladder = inputs.ladder;
  if (ladder.mesh_scales.empty())
    fail("study convergence: the mesh ladder is empty");
  const std::vector<std::string> names = ligament_names(inputs.model, inputs.flexion.ligament.name);
  std::vector<double> thickness;
  for (const pipeline::LigamentConfig& ligament : inputs.model.config.ligaments)
    thickness.push_back(ligament_thickness_mm(ligament.build));
  std::vector<double> mesh_scales = ladder.mesh_scales;
  std::sort(mesh_scales.rbegin(), mesh_scales.rend()); // coarse to fine
  std::vector<double> voxel_scales = ladder.voxel_scales;
  std::sort(voxel_scales.rbegin(), voxel_scales.rend());
  const double finest_mesh = mesh_scales.back();
  std::vector<int> orders = ladder.orders.empty() ? std::vector<int>{0} : ladder.orders;
  std::sort(orders.begin(), orders.end());
  orders.erase(std::unique(orders.begin(), orders.end()), orders.end());
  const int reference_order = orders.back(), other_order = orders.front();
  const std::string reference_family = mesh_family(reference_order);

  std::vector<RunSpec> specs;
  for (int order : orders)
    for (double s : mesh_scales)
      specs.push_back({mesh_family(order), s, 1.0, 0.0, order});
  for (double v : voxel_scales)
    specs.push_back({"quasi-static, voxel", ladder.voxel_mesh_scale, v, 0.0, other_order});
  for (double s : ladder.interactive_mesh_scales) {
    std::vector<double> steps = ladder.time_steps_s;
    std::sort(steps.rbegin(), steps.rend());
    for (double dt : steps)
      specs.push_back({fmt::format("interactive, mesh x{:g}", s), s, 1.0, dt, other_order});
  }

  // One model per (mesh, voxel) and one flexion per (model, mode, dt): shared between families.
  // Each sweep holds every ligament's figures, in the order of `names`.
  std::map<std::string, BuiltModel> models;
  std::map<std::string, std::vector<FlexionFigures>> sweeps;
  std::vector<std::vector<Run>> runs(names.size()); // per ligament
  for (std::size_t i = 0; i < specs.size(); ++i) {
    const RunSpec& spec = specs[i];
    const std::string name = model_name(spec.mesh_scale, spec.voxel_scale, spec.order);
    const std::string sweep_key = fmt::format("{}-{:g}", name, spec.time_step_s);
    log_info(fmt::format("study convergence: run {} of {}: {} ({}{})", i + 1, specs.size(),
                         spec.family, name,
                         spec.time_step_s > 0 ? fmt::format(", dt {:g} s", spec.time_step_s) : ""));
    std::string failure; // of the build or the setup: every ligament's
    try {
      if (!models.count(name))
        models[name] =
            build_model(scaled_model(inputs.model, thickness, spec), inputs.out / "models" / name);
      if (!sweeps.count(sweep_key) && models[name].any_built()) {
        sim::FlexionSettings settings = inputs.flexion;
        settings.model_dir = models[name].dir;
        settings.images = false;
        if (spec.time_step_s > 0.0) {
          settings.mode = sim::FlexionMode::interactive;
          settings.interactive.time_step_s = spec.time_step_s;
        } else {
          settings.mode = sim::FlexionMode::quasi_static;
        }
        sweeps[sweep_key] = run_flexion(settings);
      }
    } catch (const Error& e) {
      failure = e.what();
    }
    for (std::size_t l = 0; l < names.size(); ++l) {
      Run run;
      run.spec = spec;
      run.ligament = names[l];
      if (const auto model = models.find(name); model != models.end())
        run.build = model->second.ligaments.at(l);
      run.failure = failure.empty() ? run.build.failure : failure;
      const auto sweep = sweeps.find(sweep_key);
      if (run.failure.empty() && sweep != sweeps.end())
        if (const FlexionFigures* figures = figures_of(sweep->second, names[l])) {
          run.flexion = *figures;
          run.failure = figures->success ? "" : figures->failure;
        }
      if (!run.failure.empty())
        log_info(fmt::format("study convergence: {}{} failed: {}",
                             names.size() > 1 ? names[l] + " in " : "", name, run.failure));
      runs[l].push_back(run);
    }
  }

  // The reference: the finest quasi-static mesh, every ligament's.
  const std::string reference_key = model_name(finest_mesh, 1.0, reference_order) + "-0";
  const auto reference = sweeps.find(reference_key);
  const auto reference_of = [&](std::size_t l) {
    return reference == sweeps.end() ? nullptr : figures_of(reference->second, names[l]);
  };
  for (std::size_t l = 0; l < names.size(); ++l) {
    if (reference_of(l) && reference_of(l)->success)
      continue;
    std::string failure = "not run";
    for (const Run& run : runs[l])
      if (run.spec.family == reference_family && run.spec.mesh_scale == finest_mesh)
        failure = run.failure;
    fail<SolverError>("study convergence: the reference run ({}{}) failed: {}", reference_key,
                      names.size() > 1 ? ", " + names[l] : "", failure);
  }
  const std::string finest_voxel_key =
      model_name(ladder.voxel_mesh_scale, voxel_scales.empty() ? 1.0 : voxel_scales.back(),
                 other_order) +
      "-0";

  nlohmann::json report;
  nlohmann::json ligaments = nlohmann::json::array();
  int reference_tets = 0;
  std::string reference_text = "quasi-static";
  for (std::size_t l = 0; l < names.size(); ++l) {
    const FlexionFigures& own = *reference_of(l);
    nlohmann::json entry = {
        {"ligament", names[l]}, {"thickness_mm", thickness[l]}, {"reference_tets", own.tets}};
    compare_runs(runs[l], names[l], sweeps, own, reference_family, finest_voxel_key, entry);
    entry["fastest_within_1pct_femur_force"] =
        fastest_converged(runs[l], reference_family, finest_mesh);
    ligaments.push_back(entry);
    reference_tets += own.tets;
    reference_text += names.size() > 1 ? fmt::format(", {} {} tets", names[l], own.tets)
                                       : fmt::format(", {} tets", own.tets);
  }
  write_tables(runs, inputs.out, reference_text, ligaments);
  write_convergence_plot(runs, Quantity::energy, "strain energy", inputs.out / "convergence",
                         inputs.png);
  write_convergence_plot(runs, Quantity::femur_force, "femur force",
                         inputs.out / "convergence_femur_force", inputs.png);
  write_convergence_plot(runs, Quantity::regional_strain, "regional peak fiber strain",
                         inputs.out / "convergence_regional_strain", inputs.png);

  report["reference"] = {{"tets", reference_tets}, {"model", reference_key}};
  report["ligaments"] = ligaments;
  nlohmann::json entries = nlohmann::json::array();
  for (const std::vector<Run>& ligament_runs : runs)
    for (const Run& run : ligament_runs)
      entries.push_back(
          {{"ligament", run.ligament},
           {"family", run.spec.family},
           {"mesh_scale", run.spec.mesh_scale},
           {"voxel_scale", run.spec.voxel_scale},
           {"order",
            run.spec.order > 0 ? nlohmann::json(run.spec.order) : nlohmann::json("config")},
           {"time_step_s", run.spec.time_step_s},
           {"tets", run.flexion.tets},
           {"build_s", run.build.build_s},
           {"solve_s", run.flexion.solve_s},
           {"seconds_per_frame", seconds_per_frame(run)},
           {"peak_rss_mib", std::max(run.build.peak_rss_mib, run.flexion.peak_rss_mib)},
           {"energy_error", run.worst_vs_reference[0]},
           {"femur_force_error", run.worst_vs_reference[3]},
           {"regional_strain_error", run.worst_vs_reference[4]},
           {"failure", run.failure}});
  report["runs"] = entries;
  return report;
}

} // namespace ligsim::study
