#include "pipeline/study/sensitivity_study.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "pipeline/study/csv_text.hpp"
#include "pipeline/study/run_errors.hpp"
#include "pipeline/study/sensitivity_variants.hpp"
#include "pipeline/study/study_plot.hpp"
#include "pipeline/study/study_runs.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace ligsim::study {

namespace fs = std::filesystem;

namespace {

/// One ligament's sweep of one variant.
struct Outcome {
  const SensitivityVariant* variant = nullptr;
  FlexionFigures flexion;
  std::string failure;
};

/// What one ligament adds to the tables, the plot and summary.json.
struct LigamentTables {
  std::string csv, variant_rows, spread_rows, factor_rows;
  std::vector<PlotSeries> series;
  nlohmann::json variants = nlohmann::json::array();
  nlohmann::json spread = nlohmann::json::object();
  nlohmann::json factors = nlohmann::json::array();
};

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
  case Quantity::regional_strain:
    return "regional peak fiber strain (%)";
  }
  return "";
}

/// The value as shown in the tables: strains in percent.
double shown(const AngleFigures& a, Quantity q)
{
  const double v = quantity_value(a, q);
  return q == Quantity::mean_strain || q == Quantity::p95_strain || q == Quantity::regional_strain
             ? 100.0 * v
             : v;
}

/// One ligament's rows: per variant and angle (CSV), per variant at the last angle, the spread,
/// per factor; its plot curves (named by factor, prefixed by the ligament in a knee).
LigamentTables ligament_tables(const std::vector<Outcome>& outcomes, const std::string& ligament,
                               const std::string& series_prefix)
{
  const Outcome& baseline = outcomes.front();
  const std::vector<double> angles = [&] {
    std::vector<double> a;
    for (const AngleFigures& row : baseline.flexion.angles)
      a.push_back(row.angle_deg);
    return a;
  }();
  const double last = angles.back();
  LigamentTables t;
  const std::string name = csv_quoted(ligament);
  for (const Outcome& o : outcomes) {
    const std::string factor = csv_quoted(o.variant->factor);
    const std::string variant = csv_quoted(o.variant->name);
    for (const AngleFigures& a : o.flexion.angles) {
      const AngleFigures* b = at_angle(baseline.flexion, a.angle_deg);
      t.csv += fmt::format(
          "{},{},{},{},{},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.4g},\n", name, factor, variant,
          o.flexion.tets, a.angle_deg, a.strain_energy_mj, a.mean_fiber_stretch,
          a.p95_fiber_stretch, a.max_fiber_stretch, a.femur_force_n.norm(),
          b ? 100.0 * (a.femur_force_n.norm() / b->femur_force_n.norm() - 1.0) : NAN);
    }
    if (!o.failure.empty())
      t.csv += fmt::format("{},{},{},{},,,,,,,,{}\n", name, factor, variant, o.flexion.tets,
                           csv_quoted(o.failure));
  }

  // The figures at the last angle: per variant, the spread, and per factor.
  const AngleFigures& base = *at_angle(baseline.flexion, last);
  std::map<std::string, QuantityValues> squares; // by factor
  std::map<std::string, QuantityValues> largest;
  QuantityValues total{};
  std::array<std::vector<double>, kQuantities.size()> values;
  std::vector<std::string> factors;
  for (const Outcome& o : outcomes) {
    const SensitivityVariant& v = *o.variant;
    nlohmann::json entry = {{"ligament", ligament},
                            {"factor", v.factor},
                            {"variant", v.name},
                            {"description", v.description},
                            {"tets", o.flexion.tets}};
    const AngleFigures* a = o.failure.empty() ? at_angle(o.flexion, last) : nullptr;
    if (!a) {
      t.variant_rows += fmt::format("| {} | {} | {} | | failed: {} | | | | |\n", ligament, v.factor,
                                    v.name, o.failure);
      entry["failure"] = o.failure;
      t.variants.push_back(entry);
      continue;
    }
    entry.update(
        {{"strain_energy_mj", a->strain_energy_mj}, {"femur_force_n", a->femur_force_n.norm()}});
    t.variants.push_back(entry);
    t.variant_rows += fmt::format(
        "| {} | {} | {} | {} | {:.1f} | {:.2f} | {:.2f} | {:.1f} | {:+.1f} % |\n", ligament,
        v.factor, v.name, o.flexion.tets, a->strain_energy_mj, shown(*a, Quantity::mean_strain),
        shown(*a, Quantity::p95_strain), a->femur_force_n.norm(),
        100.0 * (a->femur_force_n.norm() / base.femur_force_n.norm() - 1.0));
    for (std::size_t q = 0; q < kQuantities.size(); ++q)
      values[q].push_back(shown(*a, kQuantities[q]));
    if (v.factor == "baseline")
      continue;
    if (!squares.count(v.factor)) {
      factors.push_back(v.factor);
      squares[v.factor].fill(0.0);
      largest[v.factor].fill(0.0);
    }
    for (std::size_t q = 0; q < kQuantities.size(); ++q) {
      const double change =
          quantity_value(*a, kQuantities[q]) / quantity_value(base, kQuantities[q]) - 1.0;
      squares[v.factor][q] += change * change;
      total[q] += change * change;
      if (std::abs(change) > std::abs(largest[v.factor][q]))
        largest[v.factor][q] = change;
    }
  }
  for (std::size_t q = 0; q < kQuantities.size(); ++q) {
    const auto [lo, hi] = std::minmax_element(values[q].begin(), values[q].end());
    const double b = shown(base, kQuantities[q]);
    t.spread_rows += fmt::format("| {} | {} | {:.4g} | {:.4g} | {:.4g} | {:.4g} | {:.1f} % |\n",
                                 ligament, quantity_label(kQuantities[q]), b, *lo,
                                 median(values[q]), *hi, 100.0 * (*hi - *lo) / b);
    t.spread[to_string(kQuantities[q])] = {
        {"baseline", b}, {"min", *lo}, {"median", median(values[q])}, {"max", *hi}};
  }
  for (const std::string& f : factors) {
    t.factor_rows += fmt::format("| {} | {} ", ligament, f);
    for (std::size_t q = 0; q < kQuantities.size(); ++q)
      t.factor_rows += fmt::format("| {:+.1f} % ", 100.0 * largest[f][q]);
    for (std::size_t q = 0; q < kQuantities.size(); ++q)
      t.factor_rows +=
          fmt::format("| {:.0f} % ", total[q] > 0 ? 100.0 * squares[f][q] / total[q] : 0.0);
    t.factor_rows += "|\n";
    t.factors.push_back(
        {{"factor", f},
         {"largest_femur_force_change_pct", 100.0 * largest[f][3]},
         {"femur_force_share_pct", total[3] > 0 ? 100.0 * squares[f][3] / total[3] : 0.0},
         {"largest_energy_change_pct", 100.0 * largest[f][0]},
         {"energy_share_pct", total[0] > 0 ? 100.0 * squares[f][0] / total[0] : 0.0}});
  }

  // Largest femur force change against angle, per factor.
  for (const std::string& f : factors) {
    PlotSeries series;
    series.name = series_prefix + f;
    for (double angle : angles) {
      const AngleFigures* b = at_angle(baseline.flexion, angle);
      double worst = 0.0;
      for (const Outcome& o : outcomes)
        if (o.variant->factor == f && o.failure.empty())
          if (const AngleFigures* a = at_angle(o.flexion, angle))
            worst =
                std::max(worst, std::abs(a->femur_force_n.norm() / b->femur_force_n.norm() - 1.0));
      series.x.push_back(angle);
      series.y.push_back(100.0 * worst);
    }
    t.series.push_back(series);
  }
  return t;
}

} // namespace

const std::vector<std::string>& sensitivity_factor_names()
{
  static const std::vector<std::string> names = {"offset", "smoothing", "attachment-size",
                                                 "attachment-rule", "alpha"};
  return names;
}

nlohmann::json run_sensitivity_study(const SensitivityInputs& inputs)
{
  const StudyModel source = pinned_sizes(inputs.model);
  const std::vector<std::string> names = ligament_names(source, inputs.flexion.ligament.name);
  sim::FlexionSettings settings = inputs.flexion;
  settings.mode = sim::FlexionMode::quasi_static;
  settings.images = false;
  // The baseline first: the variants keep the attachment areas its build found.
  log_info("study sensitivity: the baseline (the source segmentation and config)");
  const BuiltModel baseline = build_model(source, inputs.out / "models" / "baseline");
  for (std::size_t l = 0; l < names.size(); ++l)
    if (!baseline.ligaments[l].failure.empty())
      fail<SolverError>("study sensitivity: the baseline of {} failed: {}", names[l],
                        baseline.ligaments[l].failure);
  const std::vector<SensitivityVariant> variants =
      make_variants(source, baseline.dir, inputs.settings, inputs.out / "variants");

  std::vector<std::vector<Outcome>> outcomes(names.size()); // per ligament, per variant
  for (std::size_t i = 0; i < variants.size(); ++i) {
    const SensitivityVariant& variant = variants[i];
    log_info(fmt::format("study sensitivity: variant {} of {}: {} ({})", i + 1, variants.size(),
                         variant.name, variant.description));
    BuiltModel model;
    std::vector<FlexionFigures> figures;
    std::string failure; // of the build or the setup: every ligament's
    try {
      model = i == 0 ? baseline : build_model(variant.model, inputs.out / "models" / variant.name);
      settings.model_dir = model.dir;
      if (model.any_built())
        figures = run_flexion(settings);
    } catch (const Error& e) {
      failure = e.what();
    }
    for (std::size_t l = 0; l < names.size(); ++l) {
      Outcome outcome{&variant, {}, failure};
      if (outcome.failure.empty())
        outcome.failure = model.ligaments.at(l).failure;
      const FlexionFigures* own = figures_of(figures, names[l]);
      if (outcome.failure.empty() && own) {
        outcome.flexion = *own;
        outcome.failure = own->success ? "" : own->failure;
      }
      if (!outcome.failure.empty())
        log_info(fmt::format("study sensitivity: {}{} failed: {}",
                             names.size() > 1 ? names[l] + " in " : "", variant.name,
                             outcome.failure));
      outcomes[l].push_back(outcome);
    }
  }
  for (std::size_t l = 0; l < names.size(); ++l)
    if (!outcomes[l].front().failure.empty())
      fail<SolverError>("study sensitivity: the baseline failed{}: {}",
                        names.size() > 1 ? " (" + names[l] + ")" : "", outcomes[l].front().failure);

  const double last = outcomes.front().front().flexion.angles.back().angle_deg;
  std::string csv = "ligament,factor,variant,tets,angle_deg,strain_energy_mj,mean_fiber_stretch,"
                    "p95_fiber_stretch,max_fiber_stretch,femur_force_n,femur_force_change_pct,"
                    "failure\n";
  std::string variant_rows, spread_rows, factor_rows;
  PlotSpec spec;
  spec.title = "Segmentation sensitivity of the femur force";
  spec.x_label = "flexion angle (deg)";
  spec.y_label = "largest femur force change over the factor's variants (%)";
  nlohmann::json report;
  report["angle_deg"] = last;
  report["variants"] = nlohmann::json::array();
  for (std::size_t l = 0; l < names.size(); ++l) {
    LigamentTables t =
        ligament_tables(outcomes[l], names[l], names.size() > 1 ? names[l] + ": " : "");
    csv += t.csv;
    variant_rows += t.variant_rows;
    spread_rows += t.spread_rows;
    factor_rows += t.factor_rows;
    spec.series.insert(spec.series.end(), t.series.begin(), t.series.end());
    for (const nlohmann::json& entry : t.variants)
      report["variants"].push_back(entry);
    report["ligaments"][names[l]] = {{"spread", t.spread}, {"factors", t.factors}};
  }
  write_text_atomically(inputs.out / "sensitivity.csv", csv);
  write_text_atomically(
      inputs.out / "sensitivity.md",
      fmt::format(
          "Figures at {:g} degrees of flexion, quasi-static, no contact. Changes are relative to "
          "the ligament's baseline; a factor's share is its variants' sum of squared changes over "
          "all variants' of the ligament (one factor at a time).\n\n"
          "| ligament | factor | variant | tets | strain energy (mJ) | mean fiber strain (%) | "
          "95th pct fiber strain (%) | femur force (N) | femur force change |\n"
          "| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |\n{}"
          "\n| ligament | figure | baseline | min | median | max | (max - min) / baseline |\n"
          "| --- | --- | ---: | ---: | ---: | ---: | ---: |\n{}"
          "\n| ligament | factor | largest change: energy | mean strain | p95 strain | femur force "
          "| regional peak | share of spread: energy | mean strain | p95 strain | femur force | "
          "regional peak |\n"
          "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n{}",
          last, variant_rows, spread_rows, factor_rows));
  write_plot(spec, inputs.out / "sensitivity", inputs.png);
  return report;
}

} // namespace ligsim::study
