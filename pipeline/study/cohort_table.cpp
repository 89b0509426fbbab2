#include "pipeline/study/cohort_table.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "pipeline/study/csv_text.hpp"
#include "pipeline/study/study_plot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <set>

namespace ligsim::study {

namespace fs = std::filesystem;

namespace {

/// One ligament of a member's sweep.
struct LigamentRows {
  std::string name;
  int tets = 0;
  bool success = false;
  nlohmann::json angles;
};

struct MemberRows {
  std::string name;
  std::vector<LigamentRows> ligaments; ///< in the order the sweep had them
};

MemberRows read_member(const CohortMember& member, const std::vector<std::string>& chosen)
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
  const nlohmann::json& results = summary.contains("results") ? summary["results"] : summary;
  if (summary.value("job", "") != "flexion" || !results.contains("ligaments"))
    fail("study cohort: member '{}': {} is not the summary of `ligsim flexion` (with "
         "`results.ligaments`: one written before 2026-11-29 has a one-ligament model's results "
         "at the top; run its flexion again)",
         member.name, file.string());
  MemberRows rows;
  rows.name = member.name;
  // summary.json's objects are sorted by name: the sweep's order is in its parameters.
  std::vector<std::string> order =
      summary["parameters"].value("ligaments", std::vector<std::string>{});
  for (const auto& [name, ligament] : results["ligaments"].items())
    if (std::find(order.begin(), order.end(), name) == order.end())
      order.push_back(name);
  for (const std::string& name : order) {
    const nlohmann::json& ligament = results["ligaments"][name];
    rows.ligaments.push_back({name,
                              ligament.value("setup", nlohmann::json::object()).value("tets", 0),
                              ligament.value("success", false), ligament["angles"]});
  }
  if (chosen.empty())
    return rows;
  std::string names;
  for (const LigamentRows& ligament : rows.ligaments)
    names += (names.empty() ? "" : ", ") + ligament.name;
  std::vector<LigamentRows> kept;
  for (const std::string& name : chosen) {
    const auto found = std::find_if(rows.ligaments.begin(), rows.ligaments.end(),
                                    [&](const LigamentRows& l) { return l.name == name; });
    if (found == rows.ligaments.end())
      fail("study cohort: member '{}' has no ligament called {} (it has {})", member.name, name,
           names);
    kept.push_back(*found);
  }
  rows.ligaments = kept;
  return rows;
}

} // namespace

nlohmann::json write_cohort_table(const std::vector<CohortMember>& members, const fs::path& out,
                                  bool png, const std::vector<std::string>& ligaments)
{
  if (members.empty())
    fail("study cohort: no member given (--member NAME=FLEXION_DIR, repeatable)");
  for (const std::string& name : ligaments)
    if (std::count(ligaments.begin(), ligaments.end(), name) > 1)
      fail("study cohort: --ligaments names {} twice", name);
  std::set<std::string> names;
  std::vector<MemberRows> rows;
  bool knees = false; // some member has several ligaments
  for (const CohortMember& member : members) {
    if (!names.insert(member.name).second)
      fail("study cohort: two members are called '{}'", member.name);
    rows.push_back(read_member(member, ligaments));
    knees = knees || rows.back().ligaments.size() > 1;
  }

  std::string csv = "member,ligament,tets,angle_deg,strain_energy_mj,mean_fiber_stretch,"
                    "max_fiber_stretch,femur_force_n,converged\n";
  std::vector<double> header_angles;
  for (const auto& a : rows.front().ligaments.front().angles)
    header_angles.push_back(a.value("angle_deg", 0.0));
  std::string md = "Femur force (N) at each flexion angle (quasi-static or interactive as run, "
                   "contact as run); strain energy (mJ) at the last angle. One row per member and "
                   "ligament.\n\n| member | ligament | tets |";
  for (double angle : header_angles)
    md += fmt::format(" {:g} deg |", angle);
  md += " energy, last angle |\n| --- | --- | ---: |";
  for (std::size_t i = 0; i < header_angles.size(); ++i)
    md += " ---: |";
  md += " ---: |\n";

  PlotSpec spec;
  spec.title = "Cohort: femur force through flexion";
  spec.x_label = "flexion angle (deg)";
  spec.y_label = "femur force on the ligament (N)";
  nlohmann::json report = nlohmann::json::array();
  for (const MemberRows& m : rows)
    for (const LigamentRows& l : m.ligaments) {
      PlotSeries series;
      series.name = knees ? m.name + ": " + l.name : m.name;
      md += fmt::format("| {}{} | {} | {} |", m.name, l.success ? "" : " (stopped early)", l.name,
                        l.tets);
      for (double angle : header_angles) {
        std::string cell;
        for (const auto& a : l.angles)
          if (std::abs(a.value("angle_deg", -1.0) - angle) < 1e-9)
            cell = fmt::format("{:.1f}", a.value("femur_force_magnitude_n", 0.0));
        md += " " + cell + " |";
      }
      double last_energy = 0.0;
      for (const auto& a : l.angles) {
        const double angle = a.value("angle_deg", 0.0);
        const double force = a.value("femur_force_magnitude_n", 0.0);
        last_energy = a.value("strain_energy_mj", 0.0);
        csv += fmt::format("{},{},{},{},{:.6g},{:.6g},{:.6g},{:.6g},{}\n", csv_quoted(m.name),
                           csv_quoted(l.name), l.tets, angle, last_energy,
                           a.value("mean_fiber_stretch", 0.0), a.value("max_fiber_stretch", 0.0),
                           force, a.value("converged", false) ? 1 : 0);
        series.x.push_back(angle);
        series.y.push_back(force);
      }
      md += fmt::format(" {:.1f} |\n", last_energy);
      spec.series.push_back(series);
      report.push_back({{"member", m.name},
                        {"ligament", l.name},
                        {"tets", l.tets},
                        {"success", l.success},
                        {"angles", l.angles.size()},
                        {"last_strain_energy_mj", last_energy}});
    }
  ensure_directory(out);
  write_text_atomically(out / "cohort.csv", csv);
  write_text_atomically(out / "cohort.md", md);
  write_plot(spec, out / "cohort", png);
  return {{"members", report}};
}

} // namespace ligsim::study
