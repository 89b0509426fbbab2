// End to end: the ligsim binary on the shipped example scenes and on bad input.

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace {

struct CliRun {
  int exit_code = 0;
  std::string stderr_text;
};

CliRun run_ligsim(const std::string& arguments)
{
  const fs::path log = fs::temp_directory_path() / "ligsim_cli_test.log";
  const std::string command =
      std::string(LIGSIM_BINARY) + " -q " + arguments + " 2> " + log.string();
  CliRun run;
  const int status = std::system(command.c_str());
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  run.stderr_text = text.str();
  return run;
}

nlohmann::json read_json(const fs::path& file)
{
  std::ifstream in(file);
  return nlohmann::json::parse(in);
}

} // namespace

TEST(SimulateCli, CubeTensionSceneWritesItsOutputs)
{
  const fs::path out = fs::temp_directory_path() / "ligsim_cli_cube";
  fs::remove_all(out);
  const CliRun run = run_ligsim(
      "simulate " LIGSIM_SOURCE_DIR "/data/scenes/cube-tension.toml --out " + out.string());
  ASSERT_EQ(run.exit_code, 0) << run.stderr_text;
  EXPECT_TRUE(fs::exists(out / "series.pvd"));
  EXPECT_TRUE(fs::exists(out / "step_0005.vtu"));
  const nlohmann::json summary = read_json(out / "summary.json");
  EXPECT_TRUE(summary["results"]["success"].get<bool>());
  const auto& last = summary["results"]["steps"].back();
  // 81 top nodes at 0.05 N: the bottom carries 4.05 N.
  EXPECT_NEAR(last["reactions"]["bottom"]["force_n"][2].get<double>(), -4.05, 1e-6);
  EXPECT_TRUE(summary["stages"]["solve"].contains("peak_rss_mib"));
}

TEST(SimulateCli, SetChangesASceneKeyAndNamesItsMistakes)
{
  // Half the nodal force: half the reaction, with the scene file unchanged.
  const fs::path out = fs::temp_directory_path() / "ligsim_cli_cube_set";
  fs::remove_all(out);
  const std::string scene = LIGSIM_SOURCE_DIR "/data/scenes/cube-tension.toml";
  const CliRun run = run_ligsim("simulate " + scene +
                                " --set 'force.per_node_n=[0, 0, 0.025]' --set "
                                "solver.load_steps=2 --out " +
                                out.string());
  ASSERT_EQ(run.exit_code, 0) << run.stderr_text;
  const nlohmann::json summary = read_json(out / "summary.json");
  EXPECT_EQ(summary["results"]["steps"].size(), 2u);
  EXPECT_NEAR(summary["results"]["steps"].back()["reactions"]["bottom"]["force_n"][2].get<double>(),
              -2.025, 1e-6);
  const CliRun misspelt =
      run_ligsim("simulate " + scene + " --set solver.load_step=2 --out " + out.string() + "_bad");
  EXPECT_NE(misspelt.exit_code, 0);
  EXPECT_NE(misspelt.stderr_text.find("--set solver.load_step=2: unknown key 'load_step'"),
            std::string::npos)
      << misspelt.stderr_text;
}

TEST(SimulateCli, DynamicSceneComesToRest)
{
  const fs::path out = fs::temp_directory_path() / "ligsim_cli_dynamic";
  fs::remove_all(out);
  const CliRun run = run_ligsim(
      "simulate " LIGSIM_SOURCE_DIR "/data/scenes/cube-dynamic.toml --out " + out.string());
  ASSERT_EQ(run.exit_code, 0) << run.stderr_text;
  const nlohmann::json summary = read_json(out / "summary.json");
  EXPECT_TRUE(summary["stages"]["solve"]["reached_equilibrium"].get<bool>());
}

TEST(SimulateCli, BadSceneIsOneLineErrorAndNoOutput)
{
  const fs::path scene = fs::temp_directory_path() / "ligsim_cli_bad.toml";
  {
    std::ofstream out(scene);
    out << "[mesh]\ngenerator = \"cube\"\n[node_sets]\nb = { plane = { axis = \"w\", at_mm = 0 } "
           "}\n";
  }
  const fs::path out = fs::temp_directory_path() / "ligsim_cli_bad_out";
  fs::remove_all(out);
  const CliRun run = run_ligsim("simulate " + scene.string() + " --out " + out.string());
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_EQ(run.stderr_text.rfind("ligsim: error: ", 0), 0u) << run.stderr_text;
  EXPECT_NE(run.stderr_text.find("axis"), std::string::npos) << run.stderr_text;
  EXPECT_EQ(std::count(run.stderr_text.begin(), run.stderr_text.end(), '\n'), 1);
  EXPECT_FALSE(fs::exists(out / "summary.json"));
}

TEST(SimulateCli, BandPulledOverACylinderSceneBalancesContactAndEndForces)
{
  const fs::path out = fs::temp_directory_path() / "ligsim_cli_band_cylinder";
  fs::remove_all(out);
  const CliRun run = run_ligsim(
      "simulate " LIGSIM_SOURCE_DIR "/data/scenes/band-over-cylinder.toml --out " + out.string());
  ASSERT_EQ(run.exit_code, 0) << run.stderr_text;
  const nlohmann::json summary = read_json(out / "summary.json");
  const nlohmann::json& last = summary["results"]["steps"].back();
  const nlohmann::json& cylinder = last["contact"]["cylinder"];
  double imbalance = 0.0, contact = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double f = cylinder["force_n"][i].get<double>();
    const double ends = last["reactions"]["fixed"]["force_n"][i].get<double>() +
                        last["reactions"]["pulled"]["force_n"][i].get<double>();
    imbalance += (f + ends) * (f + ends);
    contact += f * f;
  }
  EXPECT_GT(std::sqrt(contact), 10.0); // N: the band is pulled hard over the cylinder
  EXPECT_LT(std::sqrt(imbalance), 1e-6 * std::sqrt(contact));
  EXPECT_GT(cylinder["min_gap_mm"].get<double>(), 0.0);
  EXPECT_GT(cylinder["area_mm2"].get<double>(), 5.0);
  EXPECT_TRUE(fs::exists(out / "contact" / "cylinder.vdb")); // the grid's cache
}
