/// The studies on a knee: `study convergence`, `study sensitivity` and `study cohort` on a small
/// two-ligament knee report each ligament on its own, and each ligament's rows are the ones the
/// same study gives on that ligament's one-ligament config (the ligaments never touch, and each
/// is solved on its own). Short ladders: seconds each.

#include "pipeline/study/study_model.hpp"
#include "pipeline/study/study_runs.hpp"
#include "sim/flexion/flexion_config.hpp"
#include "tests/pipeline/cli_runner.hpp"
#include "tests/pipeline/study_fixture.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

using namespace ligsim;
using namespace ligsim::test;
namespace fs = std::filesystem;

namespace {

/// The fields of a CSV line; quoted fields (RFC 4180) may hold commas.
std::vector<std::string> csv_fields(const std::string& line)
{
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == '"' && quoted && i + 1 < line.size() && line[i + 1] == '"')
      fields.back() += line[++i];
    else if (c == '"')
      quoted = !quoted;
    else if (c == ',' && !quoted)
      fields.emplace_back();
    else
      fields.back() += c;
  }
  return fields;
}

/// The rows (fields) of a CSV table whose field `column` is `value`, without that field.
std::vector<std::vector<std::string>> rows_where(const fs::path& csv, std::size_t column,
                                                 const std::string& value)
{
  std::vector<std::vector<std::string>> rows;
  const std::vector<std::string> text = lines(csv);
  for (std::size_t i = 1; i < text.size(); ++i) {
    std::vector<std::string> fields = csv_fields(text[i]);
    if (fields.at(column) != value)
      continue;
    fields.erase(fields.begin() + static_cast<std::ptrdiff_t>(column));
    rows.push_back(fields);
  }
  return rows;
}

/// A text file's lines, each ended by a newline.
std::string lines_text(const fs::path& file)
{
  std::string text;
  for (const std::string& line : lines(file))
    text += line + "\n";
  return text;
}

double field_where(const fs::path& csv, const std::string& ligament, std::size_t column,
                   std::size_t angle_column, double angle)
{
  for (const auto& row : rows_where(csv, 0, ligament))
    if (std::stod(row.at(angle_column - 1)) == angle)
      return std::stod(row.at(column - 1));
  return NAN;
}

} // namespace

TEST(StudyKnee, ConvergenceGivesEachLigamentItsOneLigamentAnswer)
{
  const StudyKnee knee("convergence");
  const std::string ladder = " --config " + knee.flexion_config.string() +
                             " --mesh-scales 1.5,1 --voxel-scales 1 --voxel-mesh-scale 1.5 "
                             "--time-steps 0.1 --interactive-mesh-scales 1.5 --no-png --out ";
  const fs::path both = fresh_folder("study_knee_convergence_" + knee.tag);
  CliResult result = run_ligsim("study convergence --model-config " + knee.knee_config.string() +
                                ladder + both.string());
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  const fs::path alone = fresh_folder("study_knee_convergence_A_" + knee.tag);
  result = run_ligsim("study convergence --model-config " + knee.ligament_configs.at("A").string() +
                      ladder + alone.string());
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;

  // Every table starts with the ligament: 4 runs (2 meshes, 1 voxel, 1 time step) x 2 angles.
  for (const char* table : {"convergence.csv", "convergence_angles.csv"})
    EXPECT_EQ(csv_fields(lines(both / table).front()).front(), "ligament") << table;
  EXPECT_EQ(lines(both / "convergence.csv").size(), 1u + 2 * 4);
  ASSERT_EQ(lines(both / "convergence_angles.csv").size(), 1u + 2 * 4 * 2);
  // A's rows are its one-ligament model's, field for field (figures and errors; the one-ligament
  // model is named by the flexion settings, MCL by default).
  const auto a_rows = rows_where(both / "convergence_angles.csv", 0, "A");
  ASSERT_EQ(a_rows.size(), 8u);
  EXPECT_EQ(a_rows, rows_where(alone / "convergence_angles.csv", 0, "MCL"));
  // B is a ligament of its own (thicker: more strain energy at 30 degrees), compared with its
  // own reference (no error on its finest mesh).
  const auto b_rows = rows_where(both / "convergence_angles.csv", 0, "B");
  ASSERT_EQ(b_rows.size(), 8u);
  EXPECT_GT(field_where(both / "convergence_angles.csv", "B", 7, 6, 30.0),
            1.2 * field_where(both / "convergence_angles.csv", "A", 7, 6, 30.0));
  EXPECT_EQ(std::stod(b_rows[3].at(11)), 0.0) << "B's finest mesh at 30 degrees";

  const nlohmann::json knee_results = read_json(both / "summary.json")["results"];
  const nlohmann::json alone_results = read_json(alone / "summary.json")["results"];
  ASSERT_EQ(knee_results["runs"].size(), 8u);
  ASSERT_EQ(alone_results["runs"].size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    const nlohmann::json& mine = knee_results["runs"][i];
    const nlohmann::json& own = alone_results["runs"][i];
    EXPECT_EQ(mine["ligament"], "A");
    EXPECT_EQ(mine["tets"], own["tets"]);
    for (const char* error : {"energy_error", "femur_force_error"})
      EXPECT_NEAR(mine[error].get<double>(), own[error].get<double>(), 1e-12) << error << i;
    EXPECT_EQ(knee_results["runs"][i + 4]["ligament"], "B");
  }
  EXPECT_GT(knee_results["runs"][0]["energy_error"].get<double>(), 1e-4); // not all zeros
  ASSERT_EQ(knee_results["ligaments"].size(), 2u);
  EXPECT_EQ(knee_results["ligaments"][0]["reference_tets"], alone_results["reference"]["tets"]);
  // The models are knees, built as `ligsim build` builds them.
  EXPECT_TRUE(fs::exists(both / "models/mesh1-voxel1/knee.json"));
  EXPECT_TRUE(fs::exists(both / "models/mesh1-voxel1/B/model.vtu"));
  EXPECT_EQ(read_json(both / "summary.json")["parameters"]["ligaments"],
            nlohmann::json({"A", "B"}));
}

TEST(StudyKnee, SensitivityChangesEveryLigamentAndReportsEachOnItsOwn)
{
  const StudyKnee knee("sensitivity");
  const std::string factors = " --config " + knee.flexion_config.string() +
                              " --factors attachment-size,alpha --attachment-changes 1 "
                              "--alphas 0.5 --no-png --out ";
  const fs::path both = fresh_folder("study_knee_sensitivity_" + knee.tag);
  CliResult result = run_ligsim("study sensitivity --model-config " + knee.knee_config.string() +
                                factors + both.string());
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  const fs::path alone = fresh_folder("study_knee_sensitivity_A_" + knee.tag);
  result = run_ligsim("study sensitivity --model-config " + knee.ligament_configs.at("A").string() +
                      factors + alone.string());
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;

  // 3 variants (baseline, areas +1 mm, alpha 0.5) x 2 angles per ligament.
  EXPECT_EQ(csv_fields(lines(both / "sensitivity.csv").front()).front(), "ligament");
  ASSERT_EQ(lines(both / "sensitivity.csv").size(), 1u + 2 * 3 * 2);
  const auto a_rows = rows_where(both / "sensitivity.csv", 0, "A");
  ASSERT_EQ(a_rows.size(), 6u);
  EXPECT_EQ(a_rows, rows_where(alone / "sensitivity.csv", 0, "MCL"));
  EXPECT_EQ(rows_where(both / "sensitivity.csv", 0, "B").size(), 6u);
  // Every ligament's surface is a variant of its own, its areas flagged.
  EXPECT_TRUE(fs::exists(both / "variants/areas+1mm/A/surface.vtp"));
  EXPECT_TRUE(fs::exists(both / "variants/areas+1mm/B/surface.vtp"));
  EXPECT_TRUE(fs::exists(alone / "variants/areas+1mm/surface.vtp"));

  const nlohmann::json results = read_json(both / "summary.json")["results"];
  const nlohmann::json own = read_json(alone / "summary.json")["results"];
  ASSERT_EQ(results["variants"].size(), 6u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(results["variants"][i]["ligament"], "A");
    EXPECT_EQ(results["variants"][i + 3]["ligament"], "B");
    EXPECT_NEAR(results["variants"][i]["femur_force_n"].get<double>(),
                own["variants"][i]["femur_force_n"].get<double>(), 1e-9);
  }
  // Growing the areas moves the force (the study compares something).
  EXPECT_NE(results["variants"][1]["femur_force_n"], results["variants"][0]["femur_force_n"]);
  for (const char* ligament : {"A", "B"}) {
    double shares = 0.0;
    for (const auto& f : results["ligaments"][ligament]["factors"])
      shares += f["femur_force_share_pct"].get<double>();
    EXPECT_NEAR(shares, 100.0, 1e-9) << ligament;
  }
  EXPECT_EQ(results["ligaments"]["A"]["spread"], only_ligament(own)["spread"]);
}

TEST(StudyKnee, CohortHasARowPerMemberLigamentAndAngle)
{
  const StudyKnee knee("cohort");
  const fs::path models = fresh_folder("study_knee_cohort_models_" + knee.tag);
  const auto build_and_flex = [&](const fs::path& config, const std::string& name) {
    CliResult result = run_ligsim("build --config " + config.string() + " --out " +
                                  (models / name / "model").string());
    EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
    result = run_ligsim("flexion --config " + knee.flexion_config.string() + " --model " +
                        (models / name / "model").string() + " --no-images --out " +
                        (models / name / "flexion").string());
    EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
    return name + "=" + (models / name / "flexion").string();
  };
  const std::string members = " --member " + build_and_flex(knee.knee_config, "knee") +
                              " --member " +
                              build_and_flex(knee.ligament_configs.at("A"), "A-alone");
  const fs::path out = fresh_folder("study_knee_cohort_" + knee.tag);
  CliResult result = run_ligsim("study cohort" + members + " --no-png --out " + out.string());
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;

  // member, ligament, then the figures: the knee's A is its one-ligament model.
  const std::vector<std::string> header = csv_fields(lines(out / "cohort.csv").front());
  EXPECT_EQ(header.at(0), "member");
  EXPECT_EQ(header.at(1), "ligament");
  ASSERT_EQ(lines(out / "cohort.csv").size(), 1u + 3 * 2); // knee A, knee B, A-alone
  const auto knee_rows = rows_where(out / "cohort.csv", 0, "knee");
  const auto alone_rows = rows_where(out / "cohort.csv", 0, "A-alone");
  ASSERT_EQ(knee_rows.size(), 4u);
  ASSERT_EQ(alone_rows.size(), 2u);
  for (std::size_t a = 0; a < 2; ++a) {
    EXPECT_EQ(knee_rows[a].at(0), "A");
    EXPECT_EQ(knee_rows[a + 2].at(0), "B");
    EXPECT_EQ(alone_rows[a].at(0), "MCL");
    EXPECT_EQ(std::vector<std::string>(knee_rows[a].begin() + 1, knee_rows[a].end()),
              std::vector<std::string>(alone_rows[a].begin() + 1, alone_rows[a].end()));
  }
  const nlohmann::json report = read_json(out / "summary.json")["results"]["members"];
  ASSERT_EQ(report.size(), 3u);
  EXPECT_EQ(report[1]["ligament"], "B");

  // One ligament of every member, and a name the knee does not have.
  result = run_ligsim("study cohort --member knee=" + (models / "knee/flexion").string() +
                      " --ligaments B --no-png --out " + out.string());
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  EXPECT_EQ(rows_where(out / "cohort.csv", 1, "B").size(), 2u);
  EXPECT_EQ(lines(out / "cohort.csv").size(), 3u);
  result = run_ligsim("study cohort" + members + " --ligaments A --no-png --out " + out.string());
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.stderr_text.find("member 'A-alone' has no ligament called A (it has MCL)"),
            std::string::npos)
      << result.stderr_text;
}

TEST(StudyKnee, ChoosesLigamentsByNameAndNamesTheOnesThereAreOnABadName)
{
  const StudyKnee knee("choose");
  const study::StudyModel b = study::load_study_model(knee.knee_config, {"B"}, "study test");
  EXPECT_TRUE(b.knee);
  ASSERT_EQ(b.config.ligaments.size(), 1u);
  EXPECT_EQ(b.config.ligaments.front().name, "B");
  EXPECT_EQ(study::ligament_names(b, "MCL"), std::vector<std::string>{"B"});
  const study::StudyModel both = study::load_study_model(knee.knee_config, {"B", "A"}, "t");
  ASSERT_EQ(both.config.ligaments.size(), 2u); // the knee's order
  EXPECT_EQ(both.config.ligaments.front().name, "A");
  const study::StudyModel one =
      study::load_study_model(knee.ligament_configs.at("A"), {}, "study test");
  EXPECT_FALSE(one.knee);
  EXPECT_EQ(study::ligament_names(one, "MCL"), std::vector<std::string>{"MCL"});

  const fs::path out = fresh_folder("study_knee_choose_" + knee.tag);
  const auto expect_error = [&](const std::string& arguments, const std::string& expected) {
    const CliResult result = run_ligsim(arguments + " --out " + out.string());
    EXPECT_NE(result.exit_code, 0) << arguments;
    EXPECT_NE(result.stderr_text.find(expected), std::string::npos) << arguments << "\n"
                                                                    << result.stderr_text;
    EXPECT_FALSE(fs::exists(out)) << arguments;
  };
  for (const char* job : {"convergence", "sensitivity"}) {
    expect_error(std::string("study ") + job + " --model-config " + knee.knee_config.string() +
                     " --ligaments A,C",
                 "has no ligament called C (it has A, B)");
    expect_error(std::string("study ") + job + " --model-config " + knee.knee_config.string() +
                     " --ligaments A,A",
                 "--ligaments names A twice");
    expect_error(std::string("study ") + job + " --model-config " +
                     knee.ligament_configs.at("A").string() + " --ligaments A",
                 "chooses among a knee config's ligaments");
  }
  expect_error("study variant --model-config " + knee.knee_config.string() +
                   " --kind offset --amount 0.2",
               "describes a knee");

  // A flexion config's [ligament] table names a ligament of the knee: a study of another one
  // sets it aside; a name the knee does not have is an error.
  const fs::path named = knee.folder / "flexion-named.toml";
  std::ofstream(named) << lines_text(knee.flexion_config)
                       << "[ligament]\nname = \"A\"\nfailure_strain = 0.1\n";
  const std::string short_ladder = " --mesh-scales 1.5 --voxel-scales 1 --voxel-mesh-scale 1.5 "
                                   "--time-steps 0.1 --interactive-mesh-scales 1.5 --no-png";
  const CliResult b_only =
      run_ligsim("study convergence --model-config " + knee.knee_config.string() + " --config " +
                 named.string() + " --ligaments B" + short_ladder + " --out " + out.string());
  EXPECT_EQ(b_only.exit_code, 0) << b_only.stderr_text;
  EXPECT_EQ(read_json(out / "summary.json")["parameters"]["ligaments"], nlohmann::json({"B"}));
  EXPECT_EQ(rows_where(out / "convergence.csv", 0, "B").size(), 3u);
  fs::remove_all(out);
  std::ofstream(named) << lines_text(knee.flexion_config) << "[ligament]\nname = \"Z\"\n";
  expect_error("study convergence --model-config " + knee.knee_config.string() + " --config " +
                   named.string() + " --ligaments B" + short_ladder,
               "the flexion config's [ligament] names Z, which the knee of");
}

TEST(StudyKnee, ALigamentThatCannotBeBuiltFailsAloneAndTheKneeKeepsTheOthers)
{
  const StudyKnee knee("partial");
  study::StudyModel model = study::load_study_model(knee.knee_config, {}, "study test");
  model.config.ligaments[0].build.surface = knee.folder / "missing-A.vtp";
  const fs::path dir = fresh_folder("study_knee_partial_" + knee.tag);
  const study::BuiltModel built = study::build_model(model, dir);
  ASSERT_EQ(built.ligaments.size(), 2u);
  EXPECT_NE(built.ligaments[0].failure.find("missing-A.vtp"), std::string::npos)
      << built.ligaments[0].failure;
  EXPECT_EQ(built.ligaments[1].failure, "");
  EXPECT_GT(built.ligaments[1].tets, 0);
  const nlohmann::json manifest = read_json(dir / "knee.json");
  ASSERT_EQ(manifest["ligaments"].size(), 1u);
  EXPECT_EQ(manifest["ligaments"][0]["name"], "B");

  // The sweep has what was built; a [ligament] table for A applies to none of it.
  sim::FlexionSettings settings;
  sim::read_flexion_config(knee.flexion_config, settings);
  settings.model_dir = dir;
  settings.ligament.name = "A";
  settings.given.insert("ligament.name");
  const std::vector<study::FlexionFigures> figures = study::run_flexion(settings);
  ASSERT_EQ(figures.size(), 1u);
  EXPECT_EQ(figures[0].ligament, "B");
  EXPECT_TRUE(figures[0].success) << figures[0].failure;
  EXPECT_EQ(study::figures_of(figures, "A"), nullptr);

  // No ligament built: each says why, and there is no knee to sweep.
  model.config.ligaments[1].build.surface = knee.folder / "missing-B.vtp";
  const study::BuiltModel none = study::build_model(model, dir);
  EXPECT_FALSE(none.any_built());
  EXPECT_NE(none.ligaments[1].failure.find("missing-B.vtp"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "knee.json"));
  EXPECT_TRUE(built.any_built());
}
