#include "pipeline/study/sensitivity_study.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "common/vtk_files.hpp"
#include "pipeline/stage_graph/stage_files.hpp"
#include "pipeline/study/convergence_study.hpp"
#include "pipeline/study/csv_text.hpp"
#include "pipeline/study/run_errors.hpp"
#include "pipeline/study/study_plot.hpp"
#include "pipeline/study/study_runs.hpp"
#include "pipeline/study/surface_variants.hpp"
#include "stages/attachments/attachments.hpp"
#include "stages/io/vtk_convert.hpp"

#include <fmt/format.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace ligsim::study {

namespace fs = std::filesystem;

namespace {

constexpr const char* kFemurArray = "study_femur_area";
constexpr const char* kTibiaArray = "study_tibia_area";

struct Variant {
  std::string factor; ///< "baseline" for the source segmentation
  std::string name;   ///< folder name, unique
  std::string description;
  pipeline::BuildConfig config;
};

struct Outcome {
  Variant variant;
  FlexionFigures flexion;
  std::string failure;
};

/// The source's attachment areas as found by the config's rules (the same call the build makes).
attachments::Attachments source_areas(const pipeline::BuildConfig& config,
                                      const TriangleSurface& surface,
                                      const std::map<std::string, Eigen::VectorXd>& arrays)
{
  const auto femur = pipeline::load_bone(config.femur);
  const auto tibia = pipeline::load_bone(config.tibia);
  attachments::Inputs inputs;
  inputs.ligament = &surface;
  inputs.femur = femur ? &*femur : nullptr;
  inputs.tibia = tibia ? &*tibia : nullptr;
  inputs.arrays = arrays;
  return attachments::find(inputs, config.femur_attachment, config.tibia_attachment);
}

/// Writes `surface` with the two areas as point-data flags and points the config at it, with
/// the "array" rule: the variant keeps exactly the areas it is given.
pipeline::BuildConfig with_surface(const pipeline::BuildConfig& source,
                                   const TriangleSurface& surface, const std::vector<int>& femur,
                                   const std::vector<int>& tibia, const fs::path& folder)
{
  ensure_directory(folder);
  auto polydata = io::to_polydata(surface);
  for (const auto& [name, area] :
       {std::pair{kFemurArray, &femur}, std::pair{kTibiaArray, &tibia}}) {
    Eigen::VectorXd flags = Eigen::VectorXd::Zero(surface.V.rows());
    for (int v : *area)
      flags(v) = 1.0;
    io::add_array(polydata->GetPointData(), name, flags);
  }
  const fs::path file = folder / "surface.vtp";
  write_vtk(polydata, file);
  pipeline::BuildConfig config = source;
  config.surface = file;
  config.femur_attachment = attachments::Rule{};
  config.femur_attachment.rule = "array";
  config.femur_attachment.array = kFemurArray;
  config.tibia_attachment = attachments::Rule{};
  config.tibia_attachment.rule = "array";
  config.tibia_attachment.array = kTibiaArray;
  return config;
}

std::string signed_label(double value, const std::string& unit)
{
  return fmt::format("{}{:g}{}", value > 0 ? "+" : "", value, unit);
}

/// The config with the sizes that default to a fraction of the ligament's thickness (voxel
/// h/8, mesh h/2, facet distance h/20) set to the source's values, so that a thinner or thicker
/// variant is meshed as finely as the source and only its shape differs.
pipeline::BuildConfig pinned_sizes(const pipeline::BuildConfig& config)
{
  pipeline::BuildConfig pinned = config;
  const double h = ligament_thickness_mm(config);
  auto pin = [](double& value, double fallback) {
    if (value <= 0.0)
      value = fallback;
  };
  pin(pinned.voxelize.spacing_mm, h / 8.0);
  pin(pinned.tetmesh.cell_size_mm, h / 2.0);
  pin(pinned.tetmesh.facet_size_mm, h / 2.0);
  pin(pinned.tetmesh.facet_distance_mm, h / 20.0);
  return pinned;
}

std::vector<Variant> make_variants(const SensitivityInputs& inputs)
{
  const pipeline::BuildConfig source = pinned_sizes(inputs.build);
  const SensitivitySettings& s = inputs.settings;
  std::map<std::string, Eigen::VectorXd> arrays;
  const TriangleSurface surface = pipeline::load_ligament(source, &arrays);
  const attachments::Attachments areas = source_areas(source, surface, arrays);
  const fs::path folders = inputs.out / "variants";
  auto surface_variant = [&](const std::string& factor, const std::string& name,
                             const std::string& description, const TriangleSurface& changed) {
    return Variant{
        factor, name, description,
        with_surface(source, changed, areas.femur.vertices, areas.tibia.vertices, folders / name)};
  };

  auto wanted = [&](const std::string& factor) {
    return s.factors.empty() ||
           std::find(s.factors.begin(), s.factors.end(), factor) != s.factors.end();
  };
  std::vector<Variant> variants;
  variants.push_back({"baseline", "baseline", "the source segmentation and config", source});
  for (double fraction :
       wanted("offset") ? std::vector<double>{-1.0, -0.5, 0.5, 1.0} : std::vector<double>{}) {
    const double d = fraction * s.offset_mm;
    variants.push_back(surface_variant("surface offset", "offset" + signed_label(d, "mm"),
                                       fmt::format("surface moved {:g} mm along its normals", d),
                                       offset_surface(surface, d)));
  }
  if (wanted("smoothing")) {
    variants.push_back(
        surface_variant("smoothing", "smoothed",
                        fmt::format("Taubin smoothing, {} iterations", s.smoothing_iterations),
                        smooth_surface(surface, s.smoothing_iterations)));
    variants.push_back(surface_variant(
        "smoothing", "roughened", fmt::format("random normal bumps, rms {:g} mm", s.roughness_mm),
        roughen_surface(surface, s.roughness_mm, 4, 12)));
  }
  for (double d : wanted("attachment-size") ? s.attachment_changes_mm : std::vector<double>{})
    variants.push_back(
        Variant{"attachment size", "areas" + signed_label(d, "mm"),
                fmt::format("both attachment areas {} by {:g} mm along the surface",
                            d > 0 ? "grown" : "shrunk", std::abs(d)),
                with_surface(source, surface, grow_area(surface, areas.femur.vertices, d),
                             grow_area(surface, areas.tibia.vertices, d),
                             folders / ("areas" + signed_label(d, "mm")))});
  if (wanted("attachment-rule")) {
    pipeline::BuildConfig config = source;
    config.tibia_attachment = attachments::Rule{};
    config.tibia_attachment.rule = "end";
    config.tibia_attachment.end_length_mm = s.tibia_end_length_mm;
    variants.push_back({"attachment rule", "tibia-end",
                        fmt::format("tibial area: the distal {:g} mm of the ligament (end rule)",
                                    s.tibia_end_length_mm),
                        config});
    config = source;
    config.centerline.span = centerline::parse_span("means");
    variants.push_back({"attachment rule", "span-means",
                        "centerline between the areas' means (the paper's rule)", config});
  }
  for (double alpha : wanted("alpha") ? s.alphas : std::vector<double>{}) {
    pipeline::BuildConfig config = source;
    config.centerline.alpha = alpha;
    variants.push_back({"alpha", fmt::format("alpha{:g}", alpha),
                        fmt::format("centerline alpha {:g}", alpha), config});
  }
  return variants;
}

double median(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

const AngleFigures* at_angle(const FlexionFigures& figures, double angle)
{
  for (const AngleFigures& a : figures.angles)
    if (std::abs(a.angle_deg - angle) < 1e-9)
      return &a;
  return nullptr;
}

std::string quantity_label(Quantity q)
{
  switch (q) {
  case Quantity::energy:
    return "strain energy (mJ)";
  case Quantity::mean_strain:
    return "mean fiber strain (%)";
  case Quantity::p95_strain:
    return "95th pct fiber strain (%)";
  case Quantity::femur_force:
    return "femur force (N)";
  }
  return "";
}

/// The value as shown in the tables: strains in percent.
double shown(const AngleFigures& a, Quantity q)
{
  const double v = quantity_value(a, q);
  return q == Quantity::mean_strain || q == Quantity::p95_strain ? 100.0 * v : v;
}

} // namespace

const std::vector<std::string>& sensitivity_factor_names()
{
  static const std::vector<std::string> names = {"offset", "smoothing", "attachment-size",
                                                 "attachment-rule", "alpha"};
  return names;
}

fs::path write_surface_variant(const pipeline::BuildConfig& config, const std::string& kind,
                               double amount, const fs::path& folder)
{
  std::map<std::string, Eigen::VectorXd> arrays;
  const TriangleSurface surface = pipeline::load_ligament(config, &arrays);
  const attachments::Attachments areas = source_areas(config, surface, arrays);
  std::vector<int> femur = areas.femur.vertices, tibia = areas.tibia.vertices;
  TriangleSurface changed = surface;
  if (kind == "offset")
    changed = offset_surface(surface, amount);
  else if (kind == "smooth")
    changed = smooth_surface(surface, static_cast<int>(std::lround(amount)));
  else if (kind == "rough")
    changed = roughen_surface(surface, amount, 4, 12);
  else if (kind == "areas") {
    femur = grow_area(surface, femur, amount);
    tibia = grow_area(surface, tibia, amount);
  } else
    fail("study variant: unknown kind '{}' (offset, smooth, rough or areas)", kind);
  if (femur.empty() || tibia.empty())
    fail("study variant: shrinking the attachment areas by {:g} mm leaves one empty", -amount);
  return with_surface(config, changed, femur, tibia, folder).surface;
}

nlohmann::json run_sensitivity_study(const SensitivityInputs& inputs)
{
  const std::vector<Variant> variants = make_variants(inputs);
  std::vector<Outcome> outcomes;
  for (std::size_t i = 0; i < variants.size(); ++i) {
    Outcome outcome{variants[i], {}, ""};
    log_info(fmt::format("study sensitivity: variant {} of {}: {} ({})", i + 1, variants.size(),
                         variants[i].name, variants[i].description));
    try {
      const BuiltModel model =
          build_model(variants[i].config, inputs.out / "models" / variants[i].name);
      sim::FlexionSettings settings = inputs.flexion;
      settings.model_dir = model.dir;
      settings.mode = sim::FlexionMode::quasi_static;
      settings.images = false;
      outcome.flexion = run_flexion(settings);
      if (!outcome.flexion.success)
        outcome.failure = outcome.flexion.failure;
    } catch (const Error& e) {
      outcome.failure = e.what();
    }
    if (!outcome.failure.empty())
      log_info(fmt::format("study sensitivity: {} failed: {}", variants[i].name, outcome.failure));
    outcomes.push_back(outcome);
  }
  const Outcome& baseline = outcomes.front();
  if (!baseline.failure.empty())
    fail<SolverError>("study sensitivity: the baseline failed: {}", baseline.failure);
  const std::vector<double> angles = [&] {
    std::vector<double> a;
    for (const AngleFigures& row : baseline.flexion.angles)
      a.push_back(row.angle_deg);
    return a;
  }();
  const double last = angles.back();

  // Per variant and angle.
  std::string csv = "factor,variant,tets,angle_deg,strain_energy_mj,mean_fiber_stretch,"
                    "p95_fiber_stretch,max_fiber_stretch,femur_force_n,femur_force_change_pct,"
                    "failure\n";
  for (const Outcome& o : outcomes) {
    for (const AngleFigures& a : o.flexion.angles) {
      const AngleFigures* b = at_angle(baseline.flexion, a.angle_deg);
      csv += fmt::format(
          "{},{},{},{},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.4g},\n", csv_quoted(o.variant.factor),
          csv_quoted(o.variant.name), o.flexion.tets, a.angle_deg, a.strain_energy_mj,
          a.mean_fiber_stretch, a.p95_fiber_stretch, a.max_fiber_stretch, a.femur_force_n.norm(),
          b ? 100.0 * (a.femur_force_n.norm() / b->femur_force_n.norm() - 1.0) : NAN);
    }
    if (!o.failure.empty())
      csv += fmt::format("{},{},{},,,,,,,,{}\n", csv_quoted(o.variant.factor),
                         csv_quoted(o.variant.name), o.flexion.tets, csv_quoted(o.failure));
  }
  write_text_atomically(inputs.out / "sensitivity.csv", csv);

  // The figures at the last angle: per variant, the spread, and per factor.
  const AngleFigures& base = *at_angle(baseline.flexion, last);
  std::string md = fmt::format(
      "Figures at {:g} degrees of flexion, quasi-static, no contact. Changes are relative to the "
      "baseline; a factor's share is its variants' sum of squared changes over all variants' "
      "(one factor at a time).\n\n"
      "| factor | variant | tets | strain energy (mJ) | mean fiber strain (%) | 95th pct fiber "
      "strain (%) | femur force (N) | femur force change |\n"
      "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |\n",
      last);
  std::map<std::string, std::array<double, 4>> squares; // by factor
  std::map<std::string, std::array<double, 4>> largest;
  std::array<double, 4> total{};
  std::array<std::vector<double>, 4> values;
  std::vector<std::string> factors;
  for (const Outcome& o : outcomes) {
    const AngleFigures* a = o.failure.empty() ? at_angle(o.flexion, last) : nullptr;
    if (!a) {
      md += fmt::format("| {} | {} | | failed: {} | | | | |\n", o.variant.factor, o.variant.name,
                        o.failure);
      continue;
    }
    md += fmt::format("| {} | {} | {} | {:.1f} | {:.2f} | {:.2f} | {:.1f} | {:+.1f} % |\n",
                      o.variant.factor, o.variant.name, o.flexion.tets, a->strain_energy_mj,
                      shown(*a, Quantity::mean_strain), shown(*a, Quantity::p95_strain),
                      a->femur_force_n.norm(),
                      100.0 * (a->femur_force_n.norm() / base.femur_force_n.norm() - 1.0));
    for (std::size_t q = 0; q < kQuantities.size(); ++q)
      values[q].push_back(shown(*a, kQuantities[q]));
    if (o.variant.factor == "baseline")
      continue;
    if (!squares.count(o.variant.factor)) {
      factors.push_back(o.variant.factor);
      squares[o.variant.factor].fill(0.0);
      largest[o.variant.factor].fill(0.0);
    }
    for (std::size_t q = 0; q < kQuantities.size(); ++q) {
      const double change =
          quantity_value(*a, kQuantities[q]) / quantity_value(base, kQuantities[q]) - 1.0;
      squares[o.variant.factor][q] += change * change;
      total[q] += change * change;
      if (std::abs(change) > std::abs(largest[o.variant.factor][q]))
        largest[o.variant.factor][q] = change;
    }
  }
  md += "\n| figure | baseline | min | median | max | (max - min) / baseline |\n"
        "| --- | ---: | ---: | ---: | ---: | ---: |\n";
  nlohmann::json spread = nlohmann::json::object();
  for (std::size_t q = 0; q < kQuantities.size(); ++q) {
    const auto [lo, hi] = std::minmax_element(values[q].begin(), values[q].end());
    const double b = shown(base, kQuantities[q]);
    md += fmt::format("| {} | {:.4g} | {:.4g} | {:.4g} | {:.4g} | {:.1f} % |\n",
                      quantity_label(kQuantities[q]), b, *lo, median(values[q]), *hi,
                      100.0 * (*hi - *lo) / b);
    spread[to_string(kQuantities[q])] = {
        {"baseline", b}, {"min", *lo}, {"median", median(values[q])}, {"max", *hi}};
  }
  md += "\n| factor | largest change: energy | mean strain | p95 strain | femur force | share of "
        "spread: energy | mean strain | p95 strain | femur force |\n"
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
  nlohmann::json factor_json = nlohmann::json::array();
  for (const std::string& f : factors) {
    md += fmt::format("| {} ", f);
    for (std::size_t q = 0; q < 4; ++q)
      md += fmt::format("| {:+.1f} % ", 100.0 * largest[f][q]);
    for (std::size_t q = 0; q < 4; ++q)
      md += fmt::format("| {:.0f} % ", total[q] > 0 ? 100.0 * squares[f][q] / total[q] : 0.0);
    md += "|\n";
    factor_json.push_back(
        {{"factor", f},
         {"largest_femur_force_change_pct", 100.0 * largest[f][3]},
         {"femur_force_share_pct", total[3] > 0 ? 100.0 * squares[f][3] / total[3] : 0.0},
         {"largest_energy_change_pct", 100.0 * largest[f][0]},
         {"energy_share_pct", total[0] > 0 ? 100.0 * squares[f][0] / total[0] : 0.0}});
  }
  write_text_atomically(inputs.out / "sensitivity.md", md);

  // Largest femur force change against angle, per factor.
  PlotSpec spec;
  spec.title = "Segmentation sensitivity of the femur force";
  spec.x_label = "flexion angle (deg)";
  spec.y_label = "largest femur force change over the factor's variants (%)";
  for (const std::string& f : factors) {
    PlotSeries series;
    series.name = f;
    for (double angle : angles) {
      const AngleFigures* b = at_angle(baseline.flexion, angle);
      double worst = 0.0;
      for (const Outcome& o : outcomes)
        if (o.variant.factor == f && o.failure.empty())
          if (const AngleFigures* a = at_angle(o.flexion, angle))
            worst =
                std::max(worst, std::abs(a->femur_force_n.norm() / b->femur_force_n.norm() - 1.0));
      series.x.push_back(angle);
      series.y.push_back(100.0 * worst);
    }
    spec.series.push_back(series);
  }
  write_plot(spec, inputs.out / "sensitivity", inputs.png);

  nlohmann::json report;
  report["angle_deg"] = last;
  report["spread"] = spread;
  report["factors"] = factor_json;
  nlohmann::json list = nlohmann::json::array();
  for (const Outcome& o : outcomes) {
    nlohmann::json entry = {{"factor", o.variant.factor},
                            {"variant", o.variant.name},
                            {"description", o.variant.description},
                            {"tets", o.flexion.tets}};
    if (const AngleFigures* a = o.failure.empty() ? at_angle(o.flexion, last) : nullptr)
      entry.update(
          {{"strain_energy_mj", a->strain_energy_mj}, {"femur_force_n", a->femur_force_n.norm()}});
    else
      entry["failure"] = o.failure;
    list.push_back(entry);
  }
  report["variants"] = list;
  return report;
}

} // namespace ligsim::study
