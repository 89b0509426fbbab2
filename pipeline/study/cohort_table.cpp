#include "pipeline/study/cohort_table.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "pipeline/study/csv_text.hpp"
#include "pipeline/study/study_plot.hpp"

#include <fmt/format.h>

#include <fstream>
#include <set>

namespace ligsim::study {

namespace fs = std::filesystem;

namespace {

struct MemberRows {
  std::string name;
  int tets = 0;
  bool success = false;
  nlohmann::json angles;
};

MemberRows read_member(const CohortMember& member)
{
  const fs::path file = member.flexion_dir / "summary.json";
  std::ifstream in(file);
  if (!in)
    fail("study cohort: member '{}': cannot read {} (the output folder of `ligsim flexion`)",
         member.name, file.string());
  nlohmann::json summary;
  try {
    summary = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    fail("study cohort: member '{}': {} is not valid JSON: {}", member.name, file.string(),
         e.what());
  }
  if (summary.value("job", "") != "flexion" || !summary.contains("results") ||
      !summary["results"].contains("angles"))
    fail("study cohort: member '{}': {} is not the summary of `ligsim flexion`", member.name,
         file.string());
  MemberRows rows;
  rows.name = member.name;
  rows.angles = summary["results"]["angles"];
  rows.success = summary["results"].value("success", false);
  if (summary.contains("stages") && summary["stages"].contains("setup"))
    rows.tets = summary["stages"]["setup"].value("tets", 0);
  return rows;
}

} // namespace

nlohmann::json write_cohort_table(const std::vector<CohortMember>& members, const fs::path& out,
                                  bool png)
{
  if (members.empty())
    fail("study cohort: no member given (--member NAME=FLEXION_DIR, repeatable)");
  std::set<std::string> names;
  std::vector<MemberRows> rows;
  for (const CohortMember& member : members) {
    if (!names.insert(member.name).second)
      fail("study cohort: two members are called '{}'", member.name);
    rows.push_back(read_member(member));
  }

  std::string csv = "member,tets,angle_deg,strain_energy_mj,mean_fiber_stretch,max_fiber_stretch,"
                    "femur_force_n,converged\n";
  std::vector<double> header_angles;
  for (const auto& a : rows.front().angles)
    header_angles.push_back(a.value("angle_deg", 0.0));
  std::string md = "Femur force (N) at each flexion angle (quasi-static or interactive as run; no "
                   "contact); strain energy (mJ) at the last angle.\n\n| member | tets |";
  for (double angle : header_angles)
    md += fmt::format(" {:g} deg |", angle);
  md += " energy, last angle |\n| --- | ---: |";
  for (std::size_t i = 0; i < header_angles.size(); ++i)
    md += " ---: |";
  md += " ---: |\n";

  PlotSpec spec;
  spec.title = "Cohort: femur force through flexion";
  spec.x_label = "flexion angle (deg)";
  spec.y_label = "femur force on the ligament (N)";
  nlohmann::json report = nlohmann::json::array();
  for (const MemberRows& m : rows) {
    PlotSeries series;
    series.name = m.name;
    md += fmt::format("| {}{} | {} |", m.name, m.success ? "" : " (stopped early)", m.tets);
    for (double angle : header_angles) {
      std::string cell;
      for (const auto& a : m.angles)
        if (std::abs(a.value("angle_deg", -1.0) - angle) < 1e-9)
          cell = fmt::format("{:.1f}", a.value("femur_force_magnitude_n", 0.0));
      md += " " + cell + " |";
    }
    double last_energy = 0.0;
    for (const auto& a : m.angles) {
      const double angle = a.value("angle_deg", 0.0);
      const double force = a.value("femur_force_magnitude_n", 0.0);
      last_energy = a.value("strain_energy_mj", 0.0);
      csv += fmt::format("{},{},{},{:.6g},{:.6g},{:.6g},{:.6g},{}\n", csv_quoted(m.name), m.tets,
                         angle, last_energy, a.value("mean_fiber_stretch", 0.0),
                         a.value("max_fiber_stretch", 0.0), force,
                         a.value("converged", false) ? 1 : 0);
      series.x.push_back(angle);
      series.y.push_back(force);
    }
    md += fmt::format(" {:.1f} |\n", last_energy);
    spec.series.push_back(series);
    report.push_back({{"member", m.name},
                      {"tets", m.tets},
                      {"success", m.success},
                      {"angles", m.angles.size()},
                      {"last_strain_energy_mj", last_energy}});
  }
  ensure_directory(out);
  write_text_atomically(out / "cohort.csv", csv);
  write_text_atomically(out / "cohort.md", md);
  write_plot(spec, out / "cohort", png);
  return {{"members", report}};
}

} // namespace ligsim::study
