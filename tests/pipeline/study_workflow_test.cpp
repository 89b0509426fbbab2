/// workflow/Snakefile end to end: a two-subject cohort (the band and a generated variant of it)
/// with `snakemake -j2`, short settings, then a second run that has nothing to do; and a cohort
/// of a knee config beside one-ligament configs, reported per ligament.

#include "tests/pipeline/cli_runner.hpp"
#include "tests/pipeline/study_fixture.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using namespace ligsim::test;
namespace fs = std::filesystem;

namespace {

struct Shell {
  int exit_code;
  std::string output;
};

Shell shell(const std::string& command, const fs::path& log)
{
  const int status = std::system((command + " > " + log.string() + " 2>&1").c_str());
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
}

/// The comma-separated fields of a line (the tables' names hold no comma).
std::vector<std::string> fields_of(const std::string& line)
{
  std::stringstream fields(line);
  std::vector<std::string> f;
  for (std::string field; std::getline(fields, field, ',');)
    f.push_back(field);
  return f;
}

} // namespace

TEST(StudyWorkflow, TwoSubjectCohortWithSnakemake)
{
  if (std::system("snakemake --version > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "snakemake is not installed (the README's apt line installs it)";
  const StudyBand band("workflow");
  const fs::path work = fresh_folder("study_workflow_" + band.tag);
  fs::create_directories(work);
  const fs::path config = work / "cohort.yaml";
  std::ofstream(config) << "ligsim: " << LIGSIM_BINARY << "\n"
                        << "results: results\n"
                        << "flexion_config: " << band.flexion_config.string() << "\n"
                        << "flexion_flags: \"--no-images\"\n"
                        << "png: true\n"
                        << "subjects:\n"
                        << "  band:\n    build_config: " << band.build_config.string() << "\n"
                        << "  band-thicker:\n    build_config: " << band.build_config.string()
                        << "\n    variant: {kind: offset, amount: 0.3}\n"
                        << "    build_flags: \"--voxel 0.8\"\n";
  const std::string snakemake = "snakemake -s " + source_path("workflow/Snakefile").string() +
                                " --configfile " + config.string() + " -d " + work.string();
  const Shell first = shell(snakemake + " -j2", work / "first.log");
  ASSERT_EQ(first.exit_code, 0) << first.output;

  // One row per subject and angle, and the thicker variant pulls harder.
  std::ifstream csv(work / "results/cohort/cohort.csv");
  std::string line;
  std::getline(csv, line);
  std::map<std::string, double> force_at_30;
  int rows = 0;
  while (std::getline(csv, line)) {
    ++rows;
    const std::vector<std::string> f = fields_of(line);
    ASSERT_EQ(f.size(), 9u) << line;
    EXPECT_EQ(f[1], "\"MCL\"") << line; // the flexion's ligament name
    if (f[3] == "30")                   // member names are quoted
      force_at_30[f[0].substr(1, f[0].size() - 2)] = std::stod(f[7]);
  }
  EXPECT_EQ(rows, 4);
  EXPECT_GT(force_at_30["band-thicker"], force_at_30["band"]);
  EXPECT_TRUE(fs::exists(work / "results/cohort/cohort.png"));
  // Only the listed subjects: the shipped config's are not merged in.
  EXPECT_FALSE(fs::exists(work / "results/vhf-right"));
  // Models carry `ligsim build`'s cache.
  EXPECT_TRUE(fs::exists(work / "results/band/model/.ligsim-cache"));

  const Shell second = shell(snakemake + " -j2 -n", work / "second.log");
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_NE(second.output.find("Nothing to be done"), std::string::npos) << second.output;
}

TEST(StudyWorkflow, KneeConfigsInACohortAreReportedPerLigament)
{
  if (std::system("snakemake --version > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "snakemake is not installed (the README's apt line installs it)";
  const StudyKnee knee("workflow");
  const fs::path work = fresh_folder("study_workflow_knee_" + knee.tag);
  fs::create_directories(work);
  // The cohort's flexion config stops at 20 degrees; the knee and A-alone name their own.
  const fs::path cohort_flexion = work / "flexion-20.toml";
  std::ofstream(cohort_flexion) << "angles_deg = [0, 20]\nimages = false\n[axis]\n"
                                   "method = \"points\"\nfirst_mm = [0, -5, 16]\n"
                                   "second_mm = [1, -5, 16]\n";
  const fs::path config = work / "cohort.yaml";
  std::ofstream(config) << "ligsim: " << LIGSIM_BINARY << "\n"
                        << "results: results\n"
                        << "flexion_config: " << cohort_flexion.string() << "\n"
                        << "flexion_flags: \"--no-images\"\n"
                        << "png: false\n"
                        << "subjects:\n"
                        << "  knee:\n    build_config: " << knee.knee_config.string() << "\n"
                        << "    flexion_config: " << knee.flexion_config.string() << "\n"
                        << "  A-alone:\n    build_config: "
                        << knee.ligament_configs.at("A").string() << "\n"
                        << "    flexion_config: " << knee.flexion_config.string() << "\n"
                        << "  B-to-20:\n    build_config: "
                        << knee.ligament_configs.at("B").string() << "\n";
  const std::string snakemake = "snakemake -s " + source_path("workflow/Snakefile").string() +
                                " --configfile " + config.string() + " -d " + work.string();
  const Shell first = shell(snakemake + " -j2", work / "first.log");
  ASSERT_EQ(first.exit_code, 0) << first.output;

  // member, ligament, tets, angle, ...: the knee's A is A's one-ligament model.
  std::map<std::string, std::vector<std::string>> rows; // "member ligament angle" -> figures
  const std::vector<std::string> table = lines(work / "results/cohort/cohort.csv");
  ASSERT_EQ(table.size(), 1u + 4 * 2); // knee A and B, A-alone, B-to-20: 2 angles each
  for (std::size_t i = 1; i < table.size(); ++i) {
    const std::vector<std::string> f = fields_of(table[i]);
    ASSERT_EQ(f.size(), 9u) << table[i];
    rows[f[0] + " " + f[1] + " " + f[3]] = std::vector<std::string>(f.begin() + 2, f.end());
  }
  for (const char* angle : {"0", "30"}) {
    ASSERT_TRUE(rows.count(std::string("\"knee\" \"A\" ") + angle)) << angle;
    ASSERT_TRUE(rows.count(std::string("\"knee\" \"B\" ") + angle)) << angle;
    EXPECT_EQ(rows[std::string("\"knee\" \"A\" ") + angle],
              rows[std::string("\"A-alone\" \"MCL\" ") + angle])
        << angle;
  }
  EXPECT_TRUE(rows.count("\"B-to-20\" \"MCL\" 20")); // the cohort's own flexion config
  EXPECT_TRUE(fs::exists(work / "results/knee/model/knee.json"));

  const Shell second = shell(snakemake + " -j2 -n", work / "second.log");
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_NE(second.output.find("Nothing to be done"), std::string::npos) << second.output;
}
