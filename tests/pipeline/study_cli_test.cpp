/// `ligsim study convergence | sensitivity | variant | cohort` end to end on the synthetic band,
/// with short ladders (a few seconds each), and the errors a user can cause.

#include "tests/pipeline/cli_runner.hpp"
#include "tests/pipeline/study_fixture.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>

using namespace ligsim::test;
namespace fs = std::filesystem;

namespace {

/// `study convergence` of the band on two meshes, one voxel size and one time step, with `more`.
CliResult run_short_convergence(const StudyBand& band, const std::string& more, const fs::path& out)
{
  return run_ligsim("study convergence --model-config " + band.build_config.string() +
                    " --config " + band.flexion_config.string() +
                    " --mesh-scales 3,2 --voxel-scales 2 --voxel-mesh-scale 3 --time-steps 0.1 "
                    "--interactive-mesh-scales 3 " +
                    more + " --out " + out.string());
}

} // namespace

TEST(StudyCli, ConvergenceLaddersAgainstTheFinestRun)
{
  const StudyBand band("convergence");
  const fs::path out = fresh_folder("study_convergence_" + band.tag);
  const CliResult result = run_short_convergence(band, "", out);
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  for (const char* file : {"convergence.csv", "convergence_angles.csv", "convergence.md",
                           "convergence.svg", "convergence.png", "convergence_femur_force.svg",
                           "convergence_regional_strain.svg", "summary.json"})
    EXPECT_TRUE(fs::exists(out / file)) << file;

  const nlohmann::json summary = read_json(out / "summary.json");
  const nlohmann::json& runs = summary["results"]["runs"];
  ASSERT_EQ(runs.size(), 4u); // 2 meshes, 1 voxel, 1 time step
  int reference_tets = summary["results"]["reference"]["tets"];
  int largest = 0;
  for (const auto& run : runs) {
    EXPECT_EQ(run["failure"], "") << run.dump();
    if (run["family"] == "quasi-static, mesh")
      largest = std::max(largest, run["tets"].get<int>());
    EXPECT_GT(run["build_s"].get<double>(), 0.0);
    EXPECT_GT(run["solve_s"].get<double>(), 0.0);
    EXPECT_GT(run["peak_rss_mib"].get<double>(), 0.0);
  }
  EXPECT_EQ(reference_tets, largest);
  // The reference run compared with itself has no error; the coarsest mesh has some.
  EXPECT_EQ(runs[1]["energy_error"].get<double>(), 0.0);
  EXPECT_GT(runs[0]["energy_error"].get<double>(), 1e-4);
  EXPECT_LT(runs[0]["energy_error"].get<double>(), 0.5);
  // The regional peak (2 mm regions) is compared too: the coarse mesh's differs from the
  // reference's.
  EXPECT_EQ(runs[1]["regional_strain_error"].get<double>(), 0.0);
  EXPECT_GT(runs[0]["regional_strain_error"].get<double>(), 0.0);
  // The interactive run on the coarsest mesh, timed per frame, its regional peak compared too.
  EXPECT_EQ(runs[3]["family"], "interactive, mesh x3");
  EXPECT_GT(runs[3]["seconds_per_frame"].get<double>(), 0.0);
  EXPECT_GT(runs[3]["regional_strain_error"].get<double>(), 0.0);

  std::ifstream png(out / "convergence.png", std::ios::binary);
  char magic[4] = {};
  png.read(magic, 4);
  EXPECT_EQ(std::string(magic + 1, 3), "PNG");

  // Models are built as `ligsim build` builds them: a rerun reuses every stage.
  const fs::path model = out / "models" / "mesh3-voxel1";
  EXPECT_TRUE(fs::exists(model / ".ligsim-cache"));
  const nlohmann::json built = read_json(model / "summary.json");
  EXPECT_EQ(built["job"], "build");
}

TEST(StudyCli, ConvergenceOfBothElementOrdersAgainstTheFinestTenNodeMesh)
{
  const StudyBand band("convergence_orders");
  const fs::path out = fresh_folder("study_convergence_orders_" + band.tag);
  const CliResult result = run_short_convergence(band, "--orders 2,1 --no-png", out);
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  const nlohmann::json summary = read_json(out / "summary.json");
  const nlohmann::json& runs = summary["results"]["runs"];
  ASSERT_EQ(runs.size(), 6u); // 2 meshes of each order, 1 voxel, 1 time step
  const std::string linear = "quasi-static, mesh, linear tets";
  const std::string quadratic = "quasi-static, mesh, 10-node tets";
  EXPECT_EQ(runs[0]["family"], linear);
  EXPECT_EQ(runs[1]["family"], linear);
  EXPECT_EQ(runs[2]["family"], quadratic);
  EXPECT_EQ(runs[3]["family"], quadratic);
  for (const auto& run : runs)
    EXPECT_EQ(run["failure"], "") << run.dump();
  // The reference is the finest 10-node mesh: compared with itself it has no error.
  EXPECT_EQ(summary["results"]["reference"]["model"], "mesh2-voxel1-order2-0");
  EXPECT_EQ(runs[3]["energy_error"].get<double>(), 0.0);
  EXPECT_EQ(runs[3]["tets"], summary["results"]["reference"]["tets"]);
  // On the same coarse mesh, 10-node tets come closer to the reference than linear ones.
  EXPECT_LT(runs[2]["femur_force_error"].get<double>(), runs[0]["femur_force_error"].get<double>());
  EXPECT_EQ(read_json(out / "models" / "mesh3-voxel1-order2" /
                      "summary.json")["stages"]["tetmesh"]["figures"]["used"]["order"],
            2);
  // The voxel and interactive runs take the lower order.
  EXPECT_TRUE(fs::exists(out / "models" / "mesh3-voxel2-order1" / "model.vtu"));
  EXPECT_EQ(runs[4]["order"], 1);
  const nlohmann::json& ligament = summary["results"]["ligaments"][0];
  ASSERT_TRUE(ligament.contains("fastest_within_1pct_femur_force"));
  const nlohmann::json& fastest = ligament["fastest_within_1pct_femur_force"];
  if (!fastest.is_null())
    EXPECT_LE(fastest["femur_force_error"].get<double>(), 0.01);
  std::ifstream md(out / "convergence.md");
  const std::string text{std::istreambuf_iterator<char>(md), {}};
  EXPECT_NE(text.find("in the least solve time"), std::string::npos);
  // --mesh-only: the mesh ladder alone, every run reused or swept again but none added.
  const CliResult mesh_only = run_short_convergence(band, "--orders 2,1 --no-png --mesh-only", out);
  ASSERT_EQ(mesh_only.exit_code, 0) << mesh_only.stderr_text;
  EXPECT_EQ(read_json(out / "summary.json")["results"]["runs"].size(), 4u);

  const CliResult bad =
      run_ligsim("study convergence --model-config " + band.build_config.string() +
                 " --orders 3 --out " + (out / "bad").string());
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.stderr_text.find("--orders"), std::string::npos) << bad.stderr_text;
}

TEST(StudyCli, SensitivitySpreadAndShares)
{
  const StudyBand band("sensitivity");
  const fs::path out = fresh_folder("study_sensitivity_" + band.tag);
  const CliResult result =
      run_ligsim("study sensitivity --model-config " + band.build_config.string() + " --config " +
                 band.flexion_config.string() +
                 " --factors offset,alpha --offset 0.3 --alphas 1 --no-png --out " + out.string());
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  const nlohmann::json results = read_json(out / "summary.json")["results"];
  ASSERT_EQ(results["variants"].size(), 6u); // baseline, 4 offsets, 1 alpha
  std::map<std::string, double> force;
  for (const auto& v : results["variants"]) {
    ASSERT_FALSE(v.contains("failure")) << v.dump();
    force[v["variant"]] = v["femur_force_n"];
  }
  // A thicker ligament (same mesh and voxel sizes) pulls harder on the femur.
  EXPECT_GT(force["offset+0.3mm"], force["offset+0.15mm"]);
  EXPECT_GT(force["offset+0.15mm"], force["baseline"]);
  EXPECT_LT(force["offset-0.3mm"], force["baseline"]);
  double shares = 0.0;
  const nlohmann::json own = only_ligament(results);
  for (const auto& f : own["factors"])
    shares += f["femur_force_share_pct"].get<double>();
  EXPECT_NEAR(shares, 100.0, 1e-9);
  const auto& spread = own["spread"]["femur_force"];
  EXPECT_LE(spread["min"].get<double>(), spread["median"].get<double>());
  EXPECT_LE(spread["median"].get<double>(), spread["max"].get<double>());
  EXPECT_NEAR(spread["max"].get<double>(), force["offset+0.3mm"], 1e-9);
  for (const char* file : {"sensitivity.csv", "sensitivity.md", "sensitivity.svg"})
    EXPECT_TRUE(fs::exists(out / file)) << file;
}

TEST(StudyCli, VariantAndCohort)
{
  const StudyBand band("cohort");
  const fs::path variant = fresh_folder("study_variant_" + band.tag);
  CliResult result = run_ligsim("study variant --model-config " + band.build_config.string() +
                                " --kind areas --amount 1 --out " + variant.string());
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  ASSERT_TRUE(fs::exists(variant / "surface.vtp"));

  const fs::path model = fresh_folder("study_variant_model_" + band.tag);
  result = run_ligsim("build --config " + band.build_config.string() + " --surface " +
                      (variant / "surface.vtp").string() +
                      " --femur-rule array --femur-array study_femur_area --tibia-rule array "
                      "--tibia-array study_tibia_area --out " +
                      model.string());
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  const fs::path flexion = fresh_folder("study_variant_flexion_" + band.tag);
  result = run_ligsim("flexion --config " + band.flexion_config.string() + " --model " +
                      model.string() + " --no-images --out " + flexion.string());
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;

  const fs::path cohort = fresh_folder("study_cohort_" + band.tag);
  result = run_ligsim("study cohort --member grown=" + flexion.string() +
                      " --member again=" + flexion.string() + " --no-png --out " + cohort.string());
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  std::ifstream csv(cohort / "cohort.csv");
  int rows = 0;
  for (std::string line; std::getline(csv, line);)
    ++rows;
  EXPECT_EQ(rows, 1 + 2 * 2); // header, 2 members x 2 angles
}

TEST(StudyCli, BadInputsGetOneClearError)
{
  const StudyBand band("bad");
  const fs::path out = fresh_folder("study_bad_" + band.tag);
  auto expect_error = [&](const std::string& arguments, const std::string& expected) {
    const CliResult result = run_ligsim(arguments);
    EXPECT_NE(result.exit_code, 0) << arguments;
    EXPECT_NE(result.stderr_text.find(expected), std::string::npos) << arguments << "\n"
                                                                    << result.stderr_text;
  };
  expect_error("study convergence --model-config " + band.build_config.string() +
                   " --mesh-scales 1,0 --out " + out.string(),
               "--mesh-scales holds 0");
  expect_error("study sensitivity --model-config " + band.build_config.string() +
                   " --alphas 2 --out " + out.string(),
               "alpha lies in [0, 1]");
  expect_error("study cohort --member nothing --out " + out.string(), "is not NAME=FLEXION_DIR");
  expect_error("study cohort --member a=" + out.string() + "/missing --out " + out.string(),
               "member 'a': cannot read");
  expect_error("study variant --model-config " + band.build_config.string() +
                   " --kind areas --amount -100 --out " + out.string(),
               "leaves one empty");
}
