/// `[tetmesh] order = 2` end to end on the synthetic band: a model of 10-node tets, its surface
/// on the ligament's, fibers at its quadrature points, footprints through its mid-edge nodes; and
/// `ligsim flexion` sweeps it and writes VTK_QUADRATIC_TETRA cells.

#include "common/vtk_files.hpp"
#include "sim/flexion/knee_model.hpp"
#include "tests/pipeline/cli_runner.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkUnstructuredGrid.h>

#include <cmath>
#include <fstream>
#include <sstream>

using namespace ligsim;
using namespace ligsim::test;
namespace fs = std::filesystem;

namespace {

/// Builds the band (made once in `shape`) with tets of `order` into a fresh folder: a config of
/// 10-node tets, which `--order 1` overrides; `flags` add to the command line.
fs::path build_band(const fs::path& shape, int order, const std::string& flags = "")
{
  return build_band_model(shape, fmt::format("quadratic_band_order_{}", order),
                          "[tetmesh]\norder = 2\n", (order == 1 ? " --order 1" : "") + flags);
}

/// The flags that give a build the cell and facet sizes the tetmesh stage of `model` used.
std::string same_sizes_as(const fs::path& model)
{
  const nlohmann::json used =
      read_json(model / "summary.json")["stages"]["tetmesh"]["figures"]["used"];
  return fmt::format(" --cell-size {} --facet-size {}", used["cell_size_mm"].get<double>(),
                     used["facet_size_mm"].get<double>());
}

/// The femur force at each angle of a sweep of `model` to 30 degrees.
std::vector<double> femur_forces(const fs::path& model, const std::string& axis)
{
  const fs::path out = fresh_folder("quadratic_band_flexion_" + model.filename().string());
  const CliResult run = run_ligsim("flexion --model " + model.string() + " " + axis +
                                   " --angles 0 15 30 --no-images --out " + out.string());
  EXPECT_EQ(run.exit_code, 0) << run.stderr_text;
  std::vector<double> forces;
  const nlohmann::json ligament_results = only_ligament(read_json(out / "summary.json")["results"]);
  for (const nlohmann::json& angle : ligament_results["angles"]) {
    EXPECT_TRUE(angle["converged"].get<bool>());
    forces.push_back(angle["femur_force_magnitude_n"].get<double>());
  }
  const auto ligament = read_vtu(out / "ligament_30.vtu");
  EXPECT_EQ(ligament->GetCellType(0),
            model.filename().string().back() == '2' ? VTK_QUADRATIC_TETRA : VTK_TETRA);
  for (const char* array : {"strain_energy_density", "fiber_stretch", "fiber_direction"})
    EXPECT_NE(ligament->GetCellData()->GetArray(array), nullptr) << array;
  return forces;
}

} // namespace

TEST(QuadraticBuild, TheBandOfTenNodeTetsIsCurvedCarriesFibersAtItsPointsAndPullsAsTheLinearOne)
{
  const fs::path shape = fresh_folder("quadratic_band_shape");
  ASSERT_EQ(run_ligsim("synth band --out " + shape.string()).exit_code, 0);
  // The 10-node band on the linear one's corners: its own default sizes are coarser.
  const fs::path linear = build_band(shape, 1);
  const fs::path quadratic = build_band(shape, 2, same_sizes_as(linear));

  const nlohmann::json curved =
      read_json(quadratic / "summary.json")["stages"]["tetmesh"]["figures"]["quadratic"];
  EXPECT_GT(curved["moved_onto_surface"].get<int>(), curved["boundary_mid_nodes"].get<int>() / 2);
  EXPECT_GE(curved["min_jacobian_ratio"].get<double>(), 0.5);
  EXPECT_EQ(read_vtu(quadratic / "model.vtu")->GetCellType(0), VTK_QUADRATIC_TETRA);

  const sim::KneeModel model = sim::load_knee_model(quadratic);
  const Eigen::Index tets = model.tet10.rows();
  ASSERT_GT(tets, 100);
  EXPECT_EQ(model.mesh.T.rows(), tets);
  EXPECT_TRUE((model.tet10.leftCols<4>().array() == model.mesh.T.array()).all());
  // One fiber at each of the 4 points, sampled there: most lie within a few degrees of their
  // tet's own (an average of 5 samples). Where the field's gradient runs along the centerline
  // (the band's ends) one sample can turn far from the average, as the stage reports.
  ASSERT_EQ(model.fiber_directions_at_points.rows(), 4 * tets);
  double sum_deg = 0.0;
  int far = 0;
  for (Eigen::Index p = 0; p < 4 * tets; ++p) {
    const double cosine =
        std::abs(model.fiber_directions_at_points.row(p).dot(model.fiber_directions.row(p / 4)));
    const double degrees = std::acos(std::min(1.0, cosine)) * 180.0 / M_PI;
    sum_deg += degrees;
    far += degrees > 30.0;
  }
  EXPECT_GT(sum_deg, 0.0); // sampled at the points, not copied
  EXPECT_LT(sum_deg / static_cast<double>(4 * tets), 5.0);
  EXPECT_LT(far, 4 * tets / 30);
  EXPECT_EQ(far,
            read_json(quadratic / "summary.json")["stages"]["fibers"]["figures"]["fibers_at_points"]
                                                 ["points_over_30_deg_from_tet_fiber"]
                                                     .get<int>());
  // A mid-edge node is bound to a bone exactly where both ends of its edge are.
  for (const std::vector<int>* nodes : {&model.femur_nodes, &model.tibia_nodes}) {
    std::vector<bool> bound(static_cast<std::size_t>(model.mesh.V.rows()), false);
    for (int n : *nodes)
      bound[static_cast<std::size_t>(n)] = true;
    int bound_mid_nodes = 0;
    for (Eigen::Index e = 0; e < tets; ++e)
      for (int k = 0; k < 6; ++k) {
        const auto [i, j] = kQuadraticTetEdges[static_cast<std::size_t>(k)];
        const bool ends = bound[static_cast<std::size_t>(model.tet10(e, i))] &&
                          bound[static_cast<std::size_t>(model.tet10(e, j))];
        EXPECT_EQ(bound[static_cast<std::size_t>(model.tet10(e, 4 + k))], ends);
        bound_mid_nodes += ends;
      }
    EXPECT_GT(bound_mid_nodes, 0);
  }

  // Its scene runs as the linear one's does (the build test's), on 10-node tets.
  const fs::path simulated = fresh_folder("quadratic_band_scene");
  const CliResult scene = run_ligsim("simulate " + (quadratic / "scene.toml").string() + " --out " +
                                     simulated.string());
  ASSERT_EQ(scene.exit_code, 0) << scene.stderr_text;
  EXPECT_TRUE(read_json(simulated / "summary.json")["results"]["success"].get<bool>());
  EXPECT_EQ(read_vtu(simulated / "step_0001.vtu")->GetCellType(0), VTK_QUADRATIC_TETRA);

  // The interactive sweep runs the corners as linear tets, and says so.
  const fs::path frames = fresh_folder("quadratic_band_frames");
  const CliResult interactive =
      run_ligsim("flexion --model " + quadratic.string() + " " + flexion_axis_argument(linear) +
                 " --mode interactive --angles 0 5 --no-images --out " + frames.string());
  ASSERT_EQ(interactive.exit_code, 0) << interactive.stderr_text;
  EXPECT_NE(read_json(frames / "summary.json")["parameters"]["elements"].get<std::string>().find(
                "linear tets on their corners"),
            std::string::npos);
  EXPECT_EQ(read_vtu(frames / "ligament_5.vtu")->GetCellType(0), VTK_TETRA);

  // The band flexes clear of the bones, stretched along its fibers: the two orders on the same
  // corners make the same ligament (the curved surface, the fibers at the points and the
  // mid-edge footprints), the quadratic one no stiffer and at most 10 % softer. Measured: linear
  // 206.0 / 315.5 / 514.1 N at 0 / 15 / 30 degrees, quadratic 197.7 / 305.4 / 514.6 N.
  const std::string axis = flexion_axis_argument(linear);
  const std::vector<double> with_linear = femur_forces(linear, axis);
  const std::vector<double> with_quadratic = femur_forces(quadratic, axis);
  ASSERT_EQ(with_linear.size(), 3u);
  ASSERT_EQ(with_quadratic.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_LT(with_quadratic[k], 1.01 * with_linear[k]) << "angle " << 15 * k;
    EXPECT_GT(with_quadratic[k], 0.9 * with_linear[k]) << "angle " << 15 * k;
  }
}
