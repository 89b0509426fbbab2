/// `ligsim tear` end to end: the files it writes, and one clear line on bad input.

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

namespace fs = std::filesystem;

struct LigsimRun {
  int status = -1;
  std::string output;
};

/// Runs ligsim with `arguments`, its output captured in `log` (one per test: ctest runs them
/// in parallel).
LigsimRun run_ligsim(const std::string& arguments, const fs::path& log)
{
  const std::string command =
      std::string(LIGSIM_BINARY) + " " + arguments + " > " + log.string() + " 2>&1";
  LigsimRun run;
  const int raw = std::system(command.c_str());
  run.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  std::ifstream in(log);
  run.output.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return run;
}

std::string scene(const std::string& name)
{
  return (fs::path(LIGSIM_SOURCE_DIR) / "data" / "scenes" / (name + ".toml")).string();
}

/// A test's own output folder (ctest runs the tests in parallel), empty.
fs::path fresh_out(const std::string& suffix)
{
  const fs::path out = fs::temp_directory_path() / ("ligsim_tear_command_test" + suffix);
  fs::remove_all(out);
  return out;
}

/// `ligsim [-q] tear SCENE --out OUT ARGUMENTS`, its output logged beside OUT.
LigsimRun tear(const std::string& scene_file, const fs::path& out, const std::string& arguments,
               bool quiet = true)
{
  return run_ligsim(std::string(quiet ? "-q " : "") + "tear " + scene_file + " --out " +
                        out.string() + " " + arguments,
                    out.string() + ".log");
}

nlohmann::json read_summary(const fs::path& out)
{
  std::ifstream in(out / "summary.json");
  return nlohmann::json::parse(in);
}

void remove_outputs(const fs::path& out)
{
  fs::remove_all(out);
  fs::remove(out.string() + ".log");
}

TEST(TearCommand, WritesFramesPngsAndSummary)
{
  const fs::path out = fresh_out("");
  const LigsimRun run =
      tear(scene("capsulorhexis"), out, "--max-steps 40 --frame-every 20 --png-size 200");
  ASSERT_EQ(run.status, 0) << run.output;
  for (const char* file : {"frames.pvd", "summary.json", "frame_00000.vtu", "frame_00000.png",
                           "frame_00001.vtu", "frame_00002.png"})
    EXPECT_TRUE(fs::is_regular_file(out / file)) << file;
  EXPECT_FALSE(fs::exists(out / "frame_00003.vtu"));

  const nlohmann::json summary = read_summary(out);
  const nlohmann::json& results = summary.at("results");
  EXPECT_EQ(summary.at("job"), "tear");
  EXPECT_EQ(results.at("steps"), 40);
  EXPECT_GT(results.at("ms_per_step").get<double>(), 0.0);
  EXPECT_GT(results.at("elements").get<int>(), 1500);
  EXPECT_GE(results.at("min_angle_deg").get<double>(), 10.0);
  for (const char* key :
       {"propagation_events", "tear_direction_deg", "tear_radius_cv", "separated"})
    EXPECT_TRUE(results.contains(key)) << key;
  remove_outputs(out);
}

TEST(TearCommand, NoPngMeansNoPng)
{
  const fs::path out = fresh_out("_nopng");
  const LigsimRun run = tear(scene("square-sheet-90"), out, "--max-steps 5 --no-png");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_TRUE(fs::is_regular_file(out / "frame_00001.vtu"));
  EXPECT_FALSE(fs::exists(out / "frame_00000.png"));
  remove_outputs(out);
}

TEST(TearCommand, SetChangesASceneKeyAndNamesItsMistakes)
{
  const fs::path out = fresh_out("_set");
  const LigsimRun run = tear(scene("square-sheet-90"), out, "--set run.max_steps=5 --no-png");
  ASSERT_EQ(run.status, 0) << run.output;
  const nlohmann::json summary = read_summary(out);
  EXPECT_EQ(summary["parameters"]["config"]["run"]["max_steps"].get<int>(), 5);
  EXPECT_EQ(summary["inputs"]["set"][0].get<std::string>(), "run.max_steps=5");
  const fs::path bad = fresh_out("_set_bad");
  const LigsimRun misspelt = tear(scene("square-sheet-90"), bad, "--set run.max_step=5", false);
  EXPECT_EQ(misspelt.status, 1);
  EXPECT_NE(misspelt.output.find("--set run.max_step=5"), std::string::npos) << misspelt.output;
  EXPECT_FALSE(fs::exists(bad));
  remove_outputs(out);
  remove_outputs(bad);
}

TEST(TearCommand, BadSceneIsOneLineAndNoOutput)
{
  const fs::path out = fresh_out("_bad");
  const LigsimRun run = tear("/nonexistent/scene.toml", out, "", false);
  EXPECT_EQ(run.status, 1);
  EXPECT_EQ(run.output, "ligsim: error: scene file /nonexistent/scene.toml does not exist\n");
  EXPECT_FALSE(fs::exists(out));
  remove_outputs(out);
}

} // namespace
