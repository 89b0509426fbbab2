/// `ligsim flexion` end to end: on the synthetic band (every output, pictures included, and the
/// bad inputs a user can give) and on the real MCL with the shipped config.

#include "common/vtk_files.hpp"
#include "tests/pipeline/cli_runner.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <vtkCellData.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

using namespace ligsim;
using namespace ligsim::test;
namespace fs = std::filesystem;

namespace {

/// The band model, built once per test process (ctest runs each test in its own process, in
/// parallel: the folder carries the process id).
const fs::path& band_model()
{
  static const fs::path model = [] {
    const std::string pid = std::to_string(::getpid());
    const fs::path shape = fresh_folder("flexion_band_shape_" + pid);
    const fs::path out = fresh_folder("flexion_band_model_" + pid);
    EXPECT_EQ(run_ligsim("synth band --out " + shape.string()).exit_code, 0);
    const CliResult built =
        run_ligsim("build --surface " + (shape / "surface.stl").string() + " --femur " +
                   (shape / "femur.stl").string() + " --tibia " + (shape / "tibia.stl").string() +
                   " --voxel 0.4 --out " + out.string());
    EXPECT_EQ(built.exit_code, 0) << built.stderr_text;
    return out;
  }();
  return model;
}

/// Runs flexion on the band expecting failure: one error line naming `expected`, and no output
/// folder.
void expect_rejected(const std::string& arguments, const std::string& expected)
{
  const fs::path out = fresh_folder("flexion_band_rejected");
  const CliResult result = run_ligsim("flexion --out " + out.string() + " " + arguments);
  EXPECT_NE(result.exit_code, 0) << arguments;
  EXPECT_NE(result.stderr_text.find(expected), std::string::npos) << result.stderr_text;
  EXPECT_EQ(std::count(result.stderr_text.begin(), result.stderr_text.end(), '\n'), 1)
      << result.stderr_text;
  EXPECT_FALSE(fs::exists(out)) << arguments;
}

} // namespace

TEST(FlexionCli, BandSweepWritesEveryOutput)
{
  const fs::path out = fresh_folder("flexion_band");
  const CliResult result =
      run_ligsim("flexion --model " + band_model().string() + " " +
                 flexion_axis_argument(band_model()) + " --out " + out.string());
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  // The closing lines say where the table and the pictures are.
  EXPECT_NE(result.stderr_text.find("flexion.csv"), std::string::npos);
  EXPECT_NE(result.stderr_text.find("ligament_45.png"), std::string::npos);

  const std::vector<std::string> table = lines(out / "flexion.csv");
  ASSERT_EQ(table.size(), 8u); // header and 0, 15, ..., 90
  for (const char* column : {"angle_deg", "strain_energy_mj", "converged", "max_fiber_stretch",
                             "femur_force_n", "tibia_force_n", "newton_iterations", "wall_s"})
    EXPECT_NE(table[0].find(column), std::string::npos) << column;
  const nlohmann::json summary = read_json(out / "summary.json");
  const nlohmann::json angles = only_ligament(summary["results"])["angles"];
  ASSERT_EQ(angles.size(), 7u);
  for (const nlohmann::json& angle : angles) {
    EXPECT_TRUE(angle["converged"].get<bool>());
    EXPECT_GT(angle["newton_iterations"].get<int>(), 0);
    const std::string label = std::to_string(angle["angle_deg"].get<int>());
    const auto ligament = read_vtu(out / ("ligament_" + label + ".vtu"));
    for (const char* array : {"strain_energy_density", "fiber_stretch", "fiber_direction"})
      EXPECT_NE(ligament->GetCellData()->GetArray(array), nullptr) << array;
    EXPECT_NE(ligament->GetPointData()->GetArray("displacement"), nullptr);
    EXPECT_GT(read_vtp(out / ("femur_" + label + ".vtp"))->GetNumberOfPoints(), 0);
  }
  EXPECT_LT(angles[0]["strain_energy_mj"].get<double>(),
            angles[6]["strain_energy_mj"].get<double>());
  EXPECT_GT(read_vtp(out / "tibia.vtp")->GetNumberOfPoints(), 0);
  EXPECT_TRUE(fs::exists(out / "flexion.pvd"));
  EXPECT_TRUE(fs::exists(out / "strain_energy.svg"));
  for (const char* picture :
       {"ligament_0.png", "ligament_45.png", "ligament_90.png", "strain_energy.png"})
    EXPECT_GT(fs::file_size(out / picture), 10000u) << picture;
}

TEST(FlexionCli, ContactKeepsTheBandOutOfTheFemurWhereItWouldCrossIt)
{
  // Without contact the synthetic band enters the femur by about 5 mm at 120 degrees (measured
  // against the femur's triangles); with contact (the default) it wraps it and stays out.
  const std::string sweep = "flexion --model " + band_model().string() + " " +
                            flexion_axis_argument(band_model()) +
                            " --angles 0,30,60,90,95,100,105,110,115,120 --no-images --out ";
  const fs::path off = fresh_folder("flexion_band_contact_off");
  ASSERT_EQ(run_ligsim(sweep + off.string() + " --contact off").exit_code, 0);
  const fs::path on = fresh_folder("flexion_band_contact_on");
  const CliResult result = run_ligsim(sweep + on.string());
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  const nlohmann::json off_summary = read_json(off / "summary.json");
  const nlohmann::json on_summary = read_json(on / "summary.json");
  const nlohmann::json without = only_ligament(off_summary["results"])["angles"];
  const nlohmann::json with = only_ligament(on_summary["results"])["angles"];
  ASSERT_EQ(with.size(), 10u);
  EXPECT_GT(without[9]["contact"]["femur"]["penetration_mm"].get<double>(), 1.0);
  EXPECT_FALSE(without[9]["contact"]["femur"].contains("force_n")); // off: measured, not solved
  for (const nlohmann::json& angle : with) {
    EXPECT_TRUE(angle["converged"].get<bool>());
    for (const char* bone : {"femur", "tibia"})
      EXPECT_LT(angle["contact"][bone]["penetration_mm"].get<double>(), 0.05) << angle.dump();
  }
  EXPECT_GT(with[9]["contact"]["femur"]["force_magnitude_n"].get<double>(), 100.0);
  EXPECT_GT(with[9]["contact"]["femur"]["area_mm2"].get<double>(), 1.0);
  // The VTUs carry the gap and the contact pressure.
  const auto ligament = read_vtu(on / "ligament_120.vtu");
  for (const char* array : {"gap_mm", "contact_pressure"})
    EXPECT_NE(ligament->GetPointData()->GetArray(array), nullptr) << array;
}

TEST(FlexionCli, InteractiveModeReportsFramesPerSecond)
{
  const fs::path out = fresh_folder("flexion_band_interactive");
  const CliResult result = run_ligsim(
      "flexion --model " + band_model().string() + " " + flexion_axis_argument(band_model()) +
      " --mode interactive --angles 0,45,90 --speed 90 --no-images --out " + out.string());
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  const nlohmann::json summary = read_json(out / "summary.json");
  EXPECT_EQ(only_ligament(summary["results"])["angles"].size(), 3u);
  EXPECT_EQ(summary["stages"]["sweep"]["frames"].get<int>(), 100);
  EXPECT_GT(summary["results"]["frames_per_second"].get<double>(), 0.0);
  EXPECT_FALSE(fs::exists(out / "ligament_45.png"));
}

TEST(FlexionCli, BadInputsAreRejectedBeforeAnythingIsWritten)
{
  const std::string model = "--model " + band_model().string();
  expect_rejected("--model /nonexistent/model " + flexion_axis_argument(band_model()),
                  "does not exist");
  expect_rejected(model + " --axis 1,2,3,1,2,3", "zero length");
  expect_rejected(model + " " + flexion_axis_argument(band_model()) + " --angles 0,45,30",
                  "increase");
  // A flag is its key set after the --set ones: it wins over them, and meets the same checks.
  expect_rejected(model + " " + flexion_axis_argument(band_model()) +
                      " --set 'angles_deg=[0, 30]' --angles 0,45,30",
                  "increase");
  expect_rejected(model, "posterior direction"); // no axis and nothing to fit it with
  expect_rejected(model + " " + flexion_axis_argument(band_model()) +
                      " --set static.max_iteration=5",
                  "--set static.max_iteration=5: unknown key 'max_iteration' in [static]");

  const fs::path config = fresh_folder("flexion_empty_angles.toml");
  std::ofstream(config) << "angles_deg = []\n";
  expect_rejected(
      model + " " + flexion_axis_argument(band_model()) + " --config " + config.string(), "empty");

  // A model folder whose bone is missing.
  const fs::path boneless = fresh_folder("flexion_boneless_model");
  fs::copy(band_model(), boneless, fs::copy_options::recursive);
  fs::remove(boneless / "tibia.vtp");
  expect_rejected("--model " + boneless.string() + " " + flexion_axis_argument(band_model()),
                  "tibia.vtp");
}

TEST(FlexionCli, TheModelsOwnMaterialAndInSituStrainAreUsedUnlessTheConfigSetsThem)
{
  const std::string pid = std::to_string(::getpid());
  const fs::path shape = fresh_folder("flexion_material_shape_" + pid);
  ASSERT_EQ(run_ligsim("synth band --out " + shape.string()).exit_code, 0);
  const fs::path config = fresh_folder("flexion_material_build.toml");
  std::ofstream(config) << "[input]\nsurface = \"" << (shape / "surface.stl").string()
                        << "\"\nfemur = \"" << (shape / "femur.stl").string() << "\"\ntibia = \""
                        << (shape / "tibia.stl").string()
                        << "\"\n[voxelize]\nspacing_mm = 0.4\n[model]\nin_situ_strain = 0.05\n"
                           "[material]\nmu_mpa = 3.5\nconvention = \"weiss\"\n";
  const fs::path model = fresh_folder("flexion_material_model");
  const CliResult built =
      run_ligsim("build --config " + config.string() + " --out " + model.string());
  ASSERT_EQ(built.exit_code, 0) << built.stderr_text;
  const auto sweep = [&](const std::string& flexion_config, const std::string& flags = "") {
    const fs::path out = fresh_folder("flexion_material");
    std::string arguments = "flexion --model " + model.string() + " " +
                            flexion_axis_argument(band_model()) +
                            " --angles 0,15 --no-images --out " + out.string() + " " + flags;
    if (!flexion_config.empty()) {
      const fs::path file = fresh_folder("flexion_material.toml");
      std::ofstream(file) << flexion_config;
      arguments += " --config " + file.string();
    }
    const CliResult result = run_ligsim(arguments);
    EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
    return only_ligament(read_json(out / "summary.json")["results"]);
  };
  const nlohmann::json own = sweep("");
  EXPECT_EQ(own["material"]["mu_mpa"].get<double>(), 3.5);
  EXPECT_EQ(own["material"]["convention"].get<std::string>(), "weiss");
  EXPECT_NEAR(own["in_situ_strain"].get<double>(), 0.05, 1e-12);
  // A [material] table with the in-situ strain alone keeps the built material.
  const nlohmann::json strain_only = sweep("[material]\nin_situ_strain = 0.01\n");
  EXPECT_EQ(strain_only["material"]["mu_mpa"].get<double>(), 3.5);
  EXPECT_EQ(strain_only["in_situ_strain"].get<double>(), 0.01);
  // Any other key sets the whole material, its missing keys at the paper's values.
  const nlohmann::json set = sweep("[material]\nc4 = 50.0\n");
  EXPECT_EQ(set["material"]["mu_mpa"].get<double>(), 27.7);
  EXPECT_EQ(set["material"]["convention"].get<std::string>(), "paper");
  EXPECT_NEAR(set["in_situ_strain"].get<double>(), 0.05, 1e-12);
  // The same key set on the command line, without a config file.
  const nlohmann::json flag = sweep("", "--set material.c4=50.0");
  EXPECT_EQ(flag["material"]["mu_mpa"].get<double>(), 27.7);
  EXPECT_EQ(flag["material"]["c4"].get<double>(), 50.0);
}

TEST(FlexionCli, RealMclSweepsToNinetyDegrees)
{
  const fs::path model = fresh_folder("flexion_mcl_model");
  const CliResult built =
      run_ligsim("build --config " + source_path("data/vhf-right-knee/mcl.toml").string() +
                 " --out " + model.string());
  ASSERT_EQ(built.exit_code, 0) << built.stderr_text;
  const fs::path out = fresh_folder("flexion_mcl");
  const CliResult result =
      run_ligsim("flexion --config " + source_path("data/vhf-right-knee/flexion.toml").string() +
                 " --model " + model.string() + " --out " + out.string());
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  const nlohmann::json summary = read_json(out / "summary.json");
  const nlohmann::json results = only_ligament(summary["results"]);
  const nlohmann::json& angles = results["angles"];
  ASSERT_EQ(angles.size(), 7u);
  for (const nlohmann::json& angle : angles)
    EXPECT_TRUE(angle["converged"].get<bool>()) << angle.dump();
  // At 0 degrees the pre-stretched MCL is in equilibrium: what the femur and the tibia exert
  // through the attachments and by contact cancels, and relaxing lowered the energy of the
  // imposed pre-stretch.
  const nlohmann::json& rest = angles[0];
  double imbalance = 0.0;
  for (int i = 0; i < 3; ++i) {
    double sum = rest["femur_force_n"][i].get<double>() + rest["tibia_force_n"][i].get<double>();
    for (const char* bone : {"femur", "tibia"})
      sum += rest["contact"][bone]["force_n"][i].get<double>();
    imbalance += sum * sum;
  }
  EXPECT_LT(std::sqrt(imbalance), 1e-6 * rest["femur_force_magnitude_n"].get<double>());
  // Contact is on by default, and no ligament node enters a bone (measured against the bone
  // triangles, not the grids the solver uses).
  for (const nlohmann::json& angle : angles)
    for (const char* bone : {"femur", "tibia"})
      EXPECT_LT(angle["contact"][bone]["penetration_mm"].get<double>(), 0.05) << angle.dump();
  EXPECT_GT(rest["mean_fiber_stretch"].get<double>(), 1.0);
  EXPECT_LT(rest["strain_energy_mj"].get<double>(),
            results["unrelaxed_prestretch_energy_mj"].get<double>());
  // The fitted axis is mediolateral (+x is lateral in this data set: see its README).
  const nlohmann::json& axis = summary["parameters"]["axis"];
  EXPECT_GT(axis["direction"][0].get<double>(), 0.95);
  for (const char* picture : {"ligament_0.png", "ligament_45.png", "ligament_90.png"})
    EXPECT_TRUE(fs::exists(out / picture)) << picture;
}
