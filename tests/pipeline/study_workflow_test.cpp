/// workflow/Snakefile end to end: a two-subject cohort (the band and a generated variant of it)
/// with `snakemake -j2`, short settings; then a second run that has nothing to do.

#include "tests/pipeline/cli_runner.hpp"
#include "tests/pipeline/study_fixture.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

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
    std::stringstream fields(line);
    std::vector<std::string> f;
    for (std::string field; std::getline(fields, field, ',');)
      f.push_back(field);
    ASSERT_EQ(f.size(), 8u) << line;
    if (f[2] == "30") // member names are quoted
      force_at_30[f[0].substr(1, f[0].size() - 2)] = std::stod(f[6]);
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
