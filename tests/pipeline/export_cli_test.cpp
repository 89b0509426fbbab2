/// `ligsim export febio` and `ligsim verify febio` end to end on a coarse synthetic band (the
/// FEBio run is skipped, saying so, where FEBio is not given: -DLIGSIM_FEBIO or $LIGSIM_FEBIO).

#include "tests/pipeline/cli_runner.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace ligsim::test;
namespace fs = std::filesystem;

namespace {

std::string febio()
{
  const char* variable = std::getenv("LIGSIM_FEBIO");
  return variable && *variable ? variable : LIGSIM_FEBIO_EXECUTABLE;
}

std::string text(const fs::path& file)
{
  std::ifstream in(file);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// A coarse band model (about 1,700 tets), built once per test process.
const fs::path& band_model()
{
  static const fs::path model = [] {
    const std::string pid = std::to_string(::getpid());
    const fs::path shape = fresh_folder("export_band_shape_" + pid);
    const fs::path out = fresh_folder("export_band_model_" + pid);
    EXPECT_EQ(run_ligsim("synth band --out " + shape.string()).exit_code, 0);
    const CliResult built = run_ligsim(
        "build --surface " + (shape / "surface.stl").string() + " --femur " +
        (shape / "femur.stl").string() + " --tibia " + (shape / "tibia.stl").string() +
        " --voxel 0.4 --cell-size 3 --facet-size 2 --facet-distance 0.3 --out " + out.string());
    EXPECT_EQ(built.exit_code, 0) << built.stderr_text;
    return out;
  }();
  return model;
}

} // namespace

TEST(ExportCli, FebioFileHoldsTheModel)
{
  const fs::path out = fresh_folder("export_feb") / "band.feb";
  const CliResult result =
      run_ligsim("export febio --model " + band_model().string() + " " +
                 flexion_axis_argument(band_model()) + " --angles 0,45 --out " + out.string());
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  // The shipped defaults use the paper's convention: the user is told FEBio's differs.
  EXPECT_NE(result.stderr_text.find("warning: the model's fiber convention is 'paper'"),
            std::string::npos);
  const std::string feb = text(out);
  std::ifstream summary_file(band_model() / "summary.json");
  const nlohmann::json figures = nlohmann::json::parse(summary_file)["stages"]["model"]["figures"];
  EXPECT_NE(feb.find("<node id=\"" + std::to_string(figures["nodes"].get<int>()) + "\">"),
            std::string::npos);
  EXPECT_NE(feb.find("<elem id=\"" + std::to_string(figures["tets"].get<int>()) + "\">"),
            std::string::npos);
  EXPECT_NE(feb.find("<time_steps>2</time_steps>"), std::string::npos);
  EXPECT_NE(feb.find("type=\"sliding-elastic\""), std::string::npos); // contact on by default
}

TEST(ExportCli, TheModelsOwnMaterialIsExportedAsTheFlexionUsesIt)
{
  // The band model as if built with [material] mu_mpa = 5 (FEBio's c1 = mu / 2).
  const fs::path model = fresh_folder("export_own_material");
  fs::copy(band_model(), model, fs::copy_options::recursive);
  std::string scene = text(model / "scene.toml");
  const std::size_t mu = scene.find("mu_mpa = ");
  ASSERT_NE(mu, std::string::npos);
  scene.replace(mu, scene.find('\n', mu) - mu, "mu_mpa = 5");
  std::ofstream(model / "scene.toml") << scene;
  const fs::path out = fresh_folder("export_own_material_feb") / "band.feb";
  const std::string command = "export febio --model " + model.string() + " " +
                              flexion_axis_argument(band_model()) + " --angles 0,45 --out " +
                              out.string();
  const CliResult result = run_ligsim(command);
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  EXPECT_NE(text(out).find("<c1>2.5</c1>"), std::string::npos);
  // A flexion config's material replaces it (its missing keys at the paper's values).
  const fs::path config = fresh_folder("export_own_material.toml");
  std::ofstream(config) << "[material]\nc4 = 61.44\n";
  ASSERT_EQ(run_ligsim(command + " --config " + config.string()).exit_code, 0);
  EXPECT_NE(text(out).find("<c1>13.85</c1>"), std::string::npos);
}

TEST(ExportCli, FebioPenaltyIsWrittenAndMustBePositive)
{
  const fs::path out = fresh_folder("export_penalty") / "band.feb";
  const std::string command = "export febio --model " + band_model().string() + " " +
                              flexion_axis_argument(band_model()) + " --angles 0,45 ";
  const CliResult result = run_ligsim(command + "--febio-penalty 3.5 --out " + out.string());
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  const std::string feb = text(out);
  EXPECT_NE(feb.find("<penalty>3.5</penalty>"), std::string::npos);
  EXPECT_EQ(feb.find("<penalty>10</penalty>"), std::string::npos);

  const fs::path bad = fresh_folder("export_penalty_bad") / "band.feb";
  const CliResult refused = run_ligsim(command + "--febio-penalty 0 --out " + bad.string());
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.stderr_text.find("--febio-penalty"), std::string::npos) << refused.stderr_text;
  EXPECT_FALSE(fs::exists(bad));
}

TEST(ExportCli, AFreeKneesPathIsExportedAsItsTableNotFoundAgain)
{
  const fs::path config = fresh_folder("export_free.toml");
  std::ofstream(config) << "[motion]\npath = \"free\"\n";
  const fs::path out = fresh_folder("export_free") / "band.feb";
  const CliResult refused = run_ligsim("export febio --model " + band_model().string() + " " +
                                       flexion_axis_argument(band_model()) + " --config " +
                                       config.string() + " --out " + out.string());
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.stderr_text.find("kinematics.csv"), std::string::npos) << refused.stderr_text;
  EXPECT_FALSE(fs::exists(out));
}

TEST(ExportCli, RejectsAnOutputThatIsNotAFebFile)
{
  const fs::path out = fresh_folder("export_bad") / "band.txt";
  const CliResult result =
      run_ligsim("export febio --model " + band_model().string() + " " +
                 flexion_axis_argument(band_model()) + " --out " + out.string());
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.stderr_text.find("ending in .feb"), std::string::npos) << result.stderr_text;
  EXPECT_FALSE(fs::exists(out));
}

TEST(ExportCli, VerifyFebioWritesTheComparison)
{
  if (febio().empty())
    GTEST_SKIP() << "FEBio not given: configure with -DLIGSIM_FEBIO=/path/to/febio4 or set "
                    "LIGSIM_FEBIO to run `ligsim verify febio`";
  const fs::path out = fresh_folder("verify_febio");
  const CliResult result = run_ligsim(
      "verify febio --model " + band_model().string() + " " + flexion_axis_argument(band_model()) +
      " --angles 0,45 --contact off --febio " + febio() + " --out " + out.string());
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  for (const char* file :
       {"knee.feb", "knee.log", "febio_comparison.csv", "febio_comparison.md", "summary.json"})
    EXPECT_TRUE(fs::exists(out / file)) << file;
  std::ifstream csv(out / "febio_comparison.csv");
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "angle_deg,ours_femur_force_n,febio_femur_force_n,ours_energy_mj,"
                  "febio_energy_mj,ours_mean_fiber_stretch,febio_mean_fiber_stretch,"
                  "ours_wall_s,febio_wall_s");
  int rows = 0;
  while (std::getline(csv, line)) {
    std::vector<double> v;
    std::stringstream fields(line);
    for (std::string field; std::getline(fields, field, ',');)
      v.push_back(std::stod(field));
    ASSERT_EQ(v.size(), 9u) << line;
    EXPECT_NEAR(v[1], v[2], 1e-6 * v[2]) << line;
    EXPECT_NEAR(v[3], v[4], 1e-6 * v[4]) << line;
    EXPECT_NEAR(v[5], v[6], 1e-8) << line;
    ++rows;
  }
  EXPECT_EQ(rows, 2);
}
