/// The error estimate of every `ligsim flexion` run, end to end on the synthetic band: `ligsim
/// build` meshes a companion with elements 1.5 times as large beside the model, the flexion sweeps
/// it through the same motion and reports each figure's grid convergence index; against a reference
/// meshed twice as fine, the estimate holds the error of the femur force and of the regional peak
/// at every angle.

#include "tests/pipeline/cli_runner.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <iterator>

using namespace ligsim::test;
namespace fs = std::filesystem;

namespace {

/// The flexion of `model` to 30 degrees: its summary's one ligament.
nlohmann::json sweep(const fs::path& model, const std::string& axis, const std::string& name,
                     const std::string& flags = "")
{
  const fs::path out = fresh_folder(name);
  const CliResult run =
      run_ligsim("flexion --model " + model.string() + " " + axis +
                 " --angles 0 15 30 --no-images " + flags + " --out " + out.string());
  EXPECT_EQ(run.exit_code, 0) << run.stderr_text;
  nlohmann::json summary = read_json(out / "summary.json");
  nlohmann::json ligament = only_ligament(summary["results"]);
  ligament["stages"] = summary["stages"];
  ligament["csv"] = lines(out / "flexion.csv");
  return ligament;
}

/// The whole content of `file`.
std::string bytes(const fs::path& file)
{
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

} // namespace

TEST(ErrorEstimateCli, TheCompanionsEstimateHoldsTheErrorAgainstAMeshTwiceAsFine)
{
  const fs::path shape = fresh_folder("estimate_band_shape");
  ASSERT_EQ(run_ligsim("synth band --out " + shape.string()).exit_code, 0);
  const fs::path model = build_band_model(shape, "estimate_band", "");
  const nlohmann::json built = read_json(model / "summary.json");
  ASSERT_TRUE(built["results"]["companion"]["built"].get<bool>()) << built["results"].dump();
  const int tets = built["stages"]["tetmesh"]["figures"]["tets"].get<int>();
  const int companion_tets = built["stages"]["companion/tetmesh"]["figures"]["tets"].get<int>();
  EXPECT_LT(companion_tets, tets * 2 / 3);
  // Its elements are 1.5 times as large, as the estimate assumes, though the band keeps its tets
  // across its thickness (sizes 1.5 times as large gave elements 1.26 times as large).
  const nlohmann::json& companion = built["results"]["companion"];
  EXPECT_NEAR(companion["size_ratio"].get<double>(), 1.5, 0.075) << companion.dump();
  EXPECT_GT(companion["sizes_scaled_by"].get<double>(), 1.5);
  // The field is the model's, linked, not recomputed: only the mesh and what follows rerun.
  EXPECT_TRUE(fs::equivalent(model / "field.vdb", model / "companion" / "field.vdb"));
  EXPECT_FALSE(built["stages"].contains("companion/field"));
  EXPECT_EQ(built["stages"]["companion/model"]["status"], "ran");
  const double cell = built["stages"]["tetmesh"]["figures"]["used"]["cell_size_mm"].get<double>();

  const std::string axis = flexion_axis_argument(model);
  const nlohmann::json estimated = sweep(model, axis, "estimate_band_flexion");
  const nlohmann::json& report = estimated["error_estimate"];
  EXPECT_TRUE(report["swept"].get<bool>());
  EXPECT_EQ(report["tets"].get<int>(), companion_tets);
  EXPECT_NEAR(report["size_ratio"].get<double>(), companion["size_ratio"].get<double>(), 0.01);
  EXPECT_TRUE(estimated["stages"].contains("error_estimate"));
  EXPECT_NE(estimated["csv"].at(0).get<std::string>().find("femur_force_error_n"),
            std::string::npos);

  // The reference: the same band meshed at half the cell size, without a companion.
  const fs::path fine =
      build_band_model(shape, "estimate_band_fine",
                       fmt::format("[tetmesh]\ncell_size_mm = {0}\nfacet_size_mm = {0}\n"
                                   "facet_distance_mm = {1}\n\n[error_estimate]\nmesh_scale = 0\n",
                                   cell / 2.0, cell / 20.0));
  EXPECT_FALSE(fs::exists(fine / "companion"));
  const nlohmann::json reference = sweep(fine, axis, "estimate_band_fine_flexion");
  EXPECT_FALSE(reference["error_estimate"]["swept"].get<bool>());
  EXPECT_NE(reference["error_estimate"]["note"].get<std::string>().find("no companion model"),
            std::string::npos);

  ASSERT_EQ(estimated["angles"].size(), 3u);
  ASSERT_EQ(reference["angles"].size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    const nlohmann::json& coarse = estimated["angles"][i];
    const nlohmann::json& exact = reference["angles"][i];
    EXPECT_FALSE(exact.contains("femur_force_error_n"));
    const double force_error = std::abs(coarse["femur_force_magnitude_n"].get<double>() -
                                        exact["femur_force_magnitude_n"].get<double>());
    const double strain_error = std::abs(coarse["max_regional_fiber_strain"].get<double>() -
                                         exact["max_regional_fiber_strain"].get<double>());
    EXPECT_GE(coarse["femur_force_error_n"].get<double>(), force_error) << "angle " << i;
    EXPECT_GE(coarse["max_regional_fiber_strain_error"].get<double>(), strain_error)
        << "angle " << i;
  }

  // --no-error-estimate: no companion solve, no estimate.
  const nlohmann::json skipped = sweep(model, axis, "estimate_band_skipped", "--no-error-estimate");
  EXPECT_FALSE(skipped.contains("error_estimate"));
  EXPECT_FALSE(skipped["stages"].contains("error_estimate"));
  for (const nlohmann::json& angle : skipped["angles"])
    EXPECT_FALSE(angle.contains("femur_force_error_n"));
}

TEST(ErrorEstimateCli, ACompanionScaleBelowThirtyPercentIsRefused)
{
  const fs::path shape = fresh_folder("estimate_refused_shape");
  ASSERT_EQ(run_ligsim("synth band --out " + shape.string()).exit_code, 0);
  const fs::path config = scratch_root() / "estimate_refused.toml";
  std::ofstream(config) << "[error_estimate]\nmesh_scale = 1.1\n";
  const fs::path out = scratch_root() / "estimate_refused";
  const CliResult built = run_ligsim("build --config " + config.string() + " --surface " +
                                     (shape / "surface.stl").string() + " --out " + out.string());
  EXPECT_NE(built.exit_code, 0);
  EXPECT_NE(built.stderr_text.find("mesh_scale must be 0"), std::string::npos) << built.stderr_text;
  EXPECT_FALSE(fs::exists(out / "model.vtu"));
}

TEST(ErrorEstimateCli, AfterOtherSizesTheCompanionIsTheOneAFreshBuildMakes)
{
  const fs::path shape = fresh_folder("estimate_sizes_shape");
  ASSERT_EQ(run_ligsim("synth band --out " + shape.string()).exit_code, 0);
  const auto build = [&](const fs::path& out, const std::string& sizes) {
    const CliResult built =
        run_ligsim("build --surface " + (shape / "surface.stl").string() + " --femur " +
                   (shape / "femur.stl").string() + " --tibia " + (shape / "tibia.stl").string() +
                   " " + sizes + " --out " + out.string());
    EXPECT_EQ(built.exit_code, 0) << built.stderr_text;
    return read_json(out / "summary.json")["results"]["companion"];
  };
  const std::string first = "--voxel 0.9 --cell-size 3 --facet-size 3 --facet-distance 0.6";
  const std::string other = "--voxel 1 --cell-size 4 --facet-size 4 --facet-distance 1";
  const fs::path fresh = fresh_folder("estimate_sizes_fresh");
  const nlohmann::json made = build(fresh, first);
  // Over a build of other sizes, the search for the first sizes' companion starts where a fresh
  // build's does, not at the factor found for the other sizes, and ends where it ends.
  const fs::path back = fresh_folder("estimate_sizes_back");
  const nlohmann::json other_made = build(back, other);
  const nlohmann::json remade = build(back, first);
  ASSERT_TRUE(made["built"].get<bool>()) << made.dump();
  ASSERT_TRUE(remade["built"].get<bool>()) << remade.dump();
  EXPECT_NE(other_made["sizes_scaled_by"], made["sizes_scaled_by"]) << other_made.dump();
  EXPECT_EQ(remade["sizes_scaled_by"], made["sizes_scaled_by"]) << remade.dump();
  EXPECT_EQ(remade["meshings"], made["meshings"]) << remade.dump();
  EXPECT_TRUE(bytes(back / "companion" / "model.vtu") == bytes(fresh / "companion" / "model.vtu"));
}
