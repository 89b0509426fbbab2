/// glTF inputs through the CLI: `file.glb#mesh` in a build config (relative to its folder), in
/// the flags, in the stage cache's key, and in `ligsim labelmap --part`.

#include "tests/pipeline/cli_runner.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>

using namespace ligsim::test;
namespace fs = std::filesystem;

namespace {

const std::string mcl = "#VH_F_left_tibial_collateral_ligament";

nlohmann::json read_summary(const fs::path& dir)
{
  std::ifstream in(dir / "summary.json");
  return nlohmann::json::parse(in);
}

std::string status(const fs::path& dir, const char* stage)
{
  return read_summary(dir)["stages"][stage]["status"].get<std::string>();
}

} // namespace

TEST(BuildGltf, ConfigPathKeepsTheMeshNameAndTheCacheKeyHoldsIt)
{
  const fs::path dir = fresh_folder("gltf_config"), out = dir / "out";
  fs::create_directories(dir);
  // The ligament file, relative to the config's folder.
  const fs::path ligaments =
      fs::relative(source_path("data/hra-knee/VH_F_Ligaments_Knee_L.glb"), dir);
  std::ofstream(dir / "build.toml")
      << "[input]\nsurface = \"" << ligaments.string() << mcl << "\"\n";
  const std::string build =
      "voxelize --config " + (dir / "build.toml").string() + " --out " + out.string();
  const CliResult first = run_ligsim(build);
  ASSERT_EQ(first.exit_code, 0) << first.stderr_text;
  EXPECT_EQ(status(out, "voxelize"), "ran");
  const nlohmann::json summary = read_summary(out);
  EXPECT_EQ(summary["inputs"]["surface"].get<std::string>(), (dir / ligaments).string() + mcl);
  EXPECT_GT(summary["stages"]["voxelize"]["figures"]["inside_voxels"].get<long>(), 1000)
      << summary["stages"]["voxelize"]["figures"].dump();

  ASSERT_EQ(run_ligsim(build).exit_code, 0);
  EXPECT_EQ(status(out, "voxelize"), "reused");
  // Another mesh of the same file: a new key.
  const CliResult other = run_ligsim(
      build + " --surface " + source_path("data/hra-knee/VH_F_Ligaments_Knee_L.glb").string() +
      "#VH_F_fibular_collateral_ligament_L");
  ASSERT_EQ(other.exit_code, 0) << other.stderr_text;
  EXPECT_EQ(status(out, "voxelize"), "ran");
}

/// The shipped female MCL keeps its footprints' rims in the mesh, so the model binds the
/// attachment areas whole: 56.2 and 300.8 of 58.1 and 305.3 mm^2 (2-core AMD EPYC, 2026-11-30),
/// where the nearest-node rule bound 41 and 237 mm^2 of them on the 2.4 mm mesh.
TEST(BuildGltf, TheShippedFemaleMclBindsItsAttachmentAreasWhole)
{
  const fs::path out = fresh_folder("gltf_shipped_mcl");
  const CliResult built =
      run_ligsim("build --config " + source_path("data/hra-knee/mcl-female.toml").string() +
                 " --out " + out.string() + " --no-images");
  ASSERT_EQ(built.exit_code, 0) << built.stderr_text;
  const nlohmann::json stages = read_summary(out)["stages"];
  const nlohmann::json& bound = stages["model"]["figures"]["footprint_area_mm2"];
  for (const char* bone : {"femur", "tibia"}) {
    const double area = stages["attachments"]["figures"][bone]["area_mm2"].get<double>();
    // The mesh's faces cut by the rim count by their centroids: 3 % off on the femoral disc.
    EXPECT_NEAR(bound[bone].get<double>(), area, 0.05 * area) << bone << ": " << bound.dump();
  }
  fs::remove_all(out);
}

TEST(BuildGltf, UnknownMeshNameIsOneClearError)
{
  const fs::path out = fresh_folder("gltf_unknown");
  const CliResult result = run_ligsim(
      "voxelize --surface " + source_path("data/hra-knee/VH_F_Ligaments_Knee_L.glb").string() +
      "#MCL --out " + out.string());
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.stderr_text.find("has no mesh named 'MCL'; its meshes: "), std::string::npos)
      << result.stderr_text;
  EXPECT_FALSE(fs::exists(out));
}

TEST(LabelmapCli, PartsAndRegionFromGltfFiles)
{
  const fs::path dir = fresh_folder("gltf_labelmap");
  fs::create_directories(dir);
  const std::string ligaments = source_path("data/hra-knee/VH_F_Ligaments_Knee_L.glb").string();
  const std::string tibia = source_path("data/hra-knee/VH_F_Knee_L.glb").string() + "#VH_F_tibia_L";
  const CliResult result =
      run_ligsim("labelmap --part " + ligaments + mcl + ":1:MCL --part " + tibia + ":2 --around " +
                 tibia + " --spacing 2 2 2 --out " + (dir / "map.nrrd").string());
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  const nlohmann::json labelmap = read_summary(dir)["stages"]["labelmap"];
  // The image covers the tibia (about 79 x 343 x 62 mm) with 10 mm all round, in 2 mm voxels.
  EXPECT_GE(labelmap["dims"][1].get<int>(), 180) << labelmap.dump();
  EXPECT_GT(labelmap["voxels_per_label"]["1"].get<long>(), 100) << labelmap.dump();
  EXPECT_GT(labelmap["voxels_per_label"]["2"].get<long>(), 10000) << labelmap.dump();
}

/// A 10 mm cube as OBJ text; `open` leaves out the two triangles of its top (z = 10).
std::string cube_obj(bool open)
{
  std::string obj = "v 0 0 0\nv 10 0 0\nv 10 10 0\nv 0 10 0\n"
                    "v 0 0 10\nv 10 0 10\nv 10 10 10\nv 0 10 10\n"
                    "f 1 3 2\nf 1 4 3\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\n"
                    "f 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";
  if (!open)
    obj += "f 5 6 7\nf 5 7 8\n";
  return obj;
}

TEST(LabelmapCli, AnOpenPartIsClosedBeforeItIsVoxelized)
{
  const fs::path dir = fresh_folder("open_part_labelmap");
  fs::create_directories(dir);
  long voxels[2] = {0, 0};
  for (const bool open : {false, true}) {
    const fs::path cube = dir / (open ? "open.obj" : "closed.obj");
    std::ofstream(cube) << cube_obj(open);
    const fs::path map = dir / (open ? "open" : "closed") / "map.nrrd";
    const CliResult result =
        run_ligsim("labelmap --part " + cube.string() +
                   ":1 --spacing 0.7 0.9 1.1 --margin 3 --out " + map.string());
    ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
    const nlohmann::json labelmap = read_summary(map.parent_path())["stages"]["labelmap"];
    voxels[open] = labelmap["voxels_per_label"]["1"].get<long>();
    if (open) {
      EXPECT_NE(labelmap["repairs_per_label"]["1"].dump().find("holes"), std::string::npos)
          << labelmap.dump();
    }
  }
  // The cube holds 10 / 0.7 x 10 / 0.9 x 10 / 1.1 voxel centres, about 1,400; the open one the
  // same once its top is filled, not the leak a column through the hole would let in.
  EXPECT_GT(voxels[0], 1000);
  EXPECT_EQ(voxels[1], voxels[0]);
}

TEST(LabelmapCli, APartThinnerThanTheSlicesIsSaidToBeInPieces)
{
  // A plate 10 x 10 mm and 0.3 mm thick, turned 45 degrees about y: at 0.3 x 0.3 x 1 mm its
  // columns hold a voxel centre now and then, in pieces, where the 10 mm cube is one piece.
  const fs::path dir = fresh_folder("thin_part_labelmap");
  fs::create_directories(dir);
  std::string plate;
  for (const double z : {-0.15, 0.15})
    for (const auto& [x, y] : {std::pair{-5.0, -5.0}, {5.0, -5.0}, {5.0, 5.0}, {-5.0, 5.0}})
      plate += fmt::format("v {} {} {}\n", (x + z) / std::sqrt(2.0), y, (z - x) / std::sqrt(2.0));
  plate += "f 1 3 2\nf 1 4 3\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\n"
           "f 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\nf 5 6 7\nf 5 7 8\n";
  std::ofstream(dir / "plate.obj") << plate;
  std::ofstream(dir / "cube.obj") << cube_obj(false);
  const CliResult result = run_ligsim("labelmap --part " + (dir / "plate.obj").string() +
                                      ":1:plate --part " + (dir / "cube.obj").string() +
                                      ":2 --margin 3 --out " + (dir / "map.nrrd").string());
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  const nlohmann::json pieces = read_summary(dir)["stages"]["labelmap"]["pieces_per_label"];
  EXPECT_GT(pieces["1"]["pieces"].get<int>(), 1) << pieces.dump();
  EXPECT_LT(pieces["1"]["largest_share"].get<double>(), 0.95) << pieces.dump();
  EXPECT_EQ(pieces["2"]["pieces"].get<int>(), 1) << pieces.dump();
  EXPECT_EQ(pieces["2"]["largest_share"].get<double>(), 1.0) << pieces.dump();
  EXPECT_NE(result.stderr_text.find("warning: label 1 'plate' is in "), std::string::npos)
      << result.stderr_text;
  EXPECT_EQ(result.stderr_text.find("warning: label 2"), std::string::npos) << result.stderr_text;
}
