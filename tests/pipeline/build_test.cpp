/// `ligsim build` end to end: on the synthetic band (cache behaviour, every output readable by
/// VTK) and on the shipped real MCL.

#include "common/vtk_files.hpp"
#include "stages/geometry/surface_query.hpp"
#include "stages/geometry/surface_topology.hpp"
#include "stages/io/surface_reader.hpp"
#include "stages/io/vtk_convert.hpp"
#include "tests/pipeline/cli_runner.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <vtkCellData.h>
#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>

#include <fstream>

using namespace ligsim;
using namespace ligsim::test;
namespace fs = std::filesystem;

namespace {

nlohmann::json read_summary(const fs::path& dir)
{
  std::ifstream in(dir / "summary.json");
  return nlohmann::json::parse(in);
}

std::map<std::string, std::string> statuses(const nlohmann::json& summary)
{
  std::map<std::string, std::string> result;
  for (const auto& [name, stage] : summary["stages"].items())
    result[name] = stage["status"];
  return result;
}

/// Reads every VTK output back with VTK's readers and checks the arrays the next stage needs.
void expect_readable_outputs(const fs::path& dir)
{
  EXPECT_GT(read_vtp(dir / "attachments.vtp")
                ->GetPointData()
                ->GetArray("femur_attachment")
                ->GetNumberOfTuples(),
            0);
  EXPECT_NE(read_vti(dir / "mask.vti")->GetPointData()->GetArray("inside"), nullptr);
  EXPECT_NE(read_vti(dir / "distance.vti")->GetPointData()->GetArray("distance"), nullptr);
  EXPECT_NE(read_vtp(dir / "centerline.vtp")->GetPointData()->GetArray("tangent"), nullptr);
  EXPECT_NE(read_vti(dir / "field.vti")->GetPointData()->GetArray("D"), nullptr);
  EXPECT_GT(read_vtu(dir / "mesh.vtu")->GetNumberOfCells(), 100);
  EXPECT_NE(read_vtu(dir / "fibers.vtu")->GetCellData()->GetArray("fiber"), nullptr);
  EXPECT_GT(read_vtp(dir / "fibers.vtp")->GetNumberOfLines(), 100);
  auto model = read_vtu(dir / "model.vtu");
  EXPECT_NE(model->GetCellData()->GetArray("fiber"), nullptr);
  EXPECT_NE(model->GetPointData()->GetArray("femur_attached"), nullptr);
  EXPECT_NE(model->GetPointData()->GetArray("tibia_attached"), nullptr);
  EXPECT_TRUE(fs::exists(dir / "scene.toml"));
}

/// Every centerline point lies inside the surface (the two extended end points on it), the line
/// passes by both attachment areas (within `near_mm` of a vertex of each), and it starts on the
/// femoral side.
void expect_centerline_inside_between_attachments(const fs::path& dir,
                                                  const TriangleSurface& surface, double near_mm)
{
  const SurfaceQuery query(surface);
  const Points line = io::points_of(read_vtp(dir / "centerline.vtp"));
  ASSERT_GT(line.rows(), 10);
  for (Eigen::Index i = 0; i < line.rows(); ++i) {
    const Eigen::Vector3d p = line.row(i);
    EXPECT_TRUE(query.inside(p) || query.distance(p) < 1e-3) << "point " << i << " outside";
  }
  auto attachments = read_vtp(dir / "attachments.vtp");
  const Points V = io::points_of(attachments);
  /// Distance from `p` to the nearest vertex of an area.
  const auto to_area = [&](const char* area, const Eigen::Vector3d& p) {
    const Eigen::MatrixXd flags = io::get_array(attachments->GetPointData(), area);
    double best = 1e300;
    for (Eigen::Index v = 0; v < V.rows(); ++v)
      if (flags(v, 0) != 0.0)
        best = std::min(best, (V.row(v).transpose() - p).norm());
    return best;
  };
  double to_femur = 1e300, to_tibia = 1e300;
  for (Eigen::Index i = 0; i < line.rows(); ++i) {
    to_femur = std::min(to_femur, to_area("femur_attachment", line.row(i).transpose()));
    to_tibia = std::min(to_tibia, to_area("tibia_attachment", line.row(i).transpose()));
  }
  EXPECT_LT(to_femur, near_mm);
  EXPECT_LT(to_tibia, near_mm);
  EXPECT_LT(to_area("femur_attachment", line.row(0).transpose()),
            to_area("tibia_attachment", line.row(0).transpose()));
}

} // namespace

TEST(Build, SyntheticBandWithCacheReuse)
{
  const fs::path shape = fresh_folder("band_shape"), out = fresh_folder("band_model");
  ASSERT_EQ(run_ligsim("synth band --out " + shape.string()).exit_code, 0);
  const std::string inputs = "--surface " + (shape / "surface.stl").string() + " --femur " +
                             (shape / "femur.stl").string() + " --tibia " +
                             (shape / "tibia.stl").string() + " --voxel 0.4 --out " + out.string();
  const CliResult first = run_ligsim("build " + inputs);
  ASSERT_EQ(first.exit_code, 0) << first.stderr_text;
  for (const auto& [name, status] : statuses(read_summary(out)))
    EXPECT_EQ(status, "ran") << name;
  expect_readable_outputs(out);
  expect_centerline_inside_between_attachments(out, io::read_surface(shape / "surface.stl"), 2.0);
  const nlohmann::json summary = read_summary(out);
  EXPECT_NE(summary["stages"]["attachments"]["figures"]["femur"]["rule"].get<std::string>().find(
                "proximity"),
            std::string::npos);
  EXPECT_GT(summary["stages"]["model"]["figures"]["femur_nodes"].get<int>(), 0);
  EXPECT_GT(summary["stages"]["model"]["figures"]["tibia_nodes"].get<int>(), 0);

  // The model's scene is one the simulator runs: the knee flexion converges at every step.
  const fs::path simulated = fresh_folder("band_flexion");
  const CliResult flexion =
      run_ligsim("simulate " + (out / "scene.toml").string() + " --out " + simulated.string());
  ASSERT_EQ(flexion.exit_code, 0) << flexion.stderr_text;
  const nlohmann::json run = read_summary(simulated);
  EXPECT_TRUE(run["results"]["success"].get<bool>());
  EXPECT_EQ(run["results"]["steps"].size(), 6u);
  EXPECT_GT(run["parameters"]["node_sets"]["femur"].get<int>(), 0);

  // Nothing changed: every stage is reused.
  ASSERT_EQ(run_ligsim("build " + inputs).exit_code, 0);
  for (const auto& [name, status] : statuses(read_summary(out)))
    EXPECT_EQ(status, "reused") << name;

  // A centerline parameter changed: it and what follows rerun, the rest is reused.
  ASSERT_EQ(run_ligsim("build " + inputs + " --alpha 0.5").exit_code, 0);
  const auto after = statuses(read_summary(out));
  for (const char* stage : {"attachments", "voxelize", "distance", "tetmesh"})
    EXPECT_EQ(after.at(stage), "reused") << stage;
  for (const char* stage : {"centerline", "field", "fibers", "model"})
    EXPECT_EQ(after.at(stage), "ran") << stage;

  // --set reaches the same key as the flag: the same parameters, every stage reused.
  ASSERT_EQ(run_ligsim("build " + inputs + " --set centerline.alpha=0.5").exit_code, 0);
  for (const auto& [name, status] : statuses(read_summary(out)))
    EXPECT_EQ(status, "reused") << name;
  EXPECT_EQ(read_summary(out)["inputs"]["set"][0], "centerline.alpha=0.5");
  // A misspelt key is refused, named, before anything is written.
  const CliResult misspelt = run_ligsim("build " + inputs + " --set centerline.alfa=0.5");
  EXPECT_NE(misspelt.exit_code, 0);
  EXPECT_NE(misspelt.stderr_text.find("--set centerline.alfa=0.5: unknown key 'alfa'"),
            std::string::npos)
      << misspelt.stderr_text;
  EXPECT_EQ(read_summary(out)["inputs"]["set"][0], "centerline.alpha=0.5");
  // A flag is its key set after the --set ones: it wins (the centerline would rerun at 0.3).
  ASSERT_EQ(run_ligsim("build " + inputs + " --set centerline.alpha=0.3 --alpha 0.5").exit_code, 0);
  for (const auto& [name, status] : statuses(read_summary(out)))
    EXPECT_EQ(status, "reused") << name;
  EXPECT_EQ(read_summary(out)["parameters"]["centerline"]["alpha"], 0.5);
}

/// The bound footprint areas (the model stage's `footprint_area_mm2`) of the band built with
/// cells and facets of `size_mm` and `footprint_rims` as given.
std::pair<double, double> bound_areas(const fs::path& shape, double size_mm, bool rims)
{
  const fs::path out = build_band_model(
      shape, fmt::format("band_rims_{}_{}", size_mm, rims),
      fmt::format("[tetmesh]\ncell_size_mm = {0}\nfacet_size_mm = {0}\nfacet_distance_mm = "
                  "0.3\nfootprint_rims = {1}\n\n[error_estimate]\nmesh_scale = 0\n",
                  size_mm, rims));
  const nlohmann::json areas =
      read_json(out / "summary.json")["stages"]["model"]["figures"]["footprint_area_mm2"];
  return {areas["femur"].get<double>(), areas["tibia"].get<double>()};
}

TEST(Build, WithTheirRimsKeptTwoMeshesBindTheSameFootprints)
{
  const fs::path shape = fresh_folder("band_rims_shape");
  ASSERT_EQ(run_ligsim("synth band --out " + shape.string()).exit_code, 0);
  // Measured: femoral 50.0 and 49.8 mm^2, tibial 255.7 and 254.2 mm^2 with the rims kept on
  // meshes of 2 and 3 mm; 49.3 and 51.9 mm^2 (5 % apart) without them.
  const auto [femur_fine, tibia_fine] = bound_areas(shape, 2.0, true);
  const auto [femur_coarse, tibia_coarse] = bound_areas(shape, 3.0, true);
  EXPECT_NEAR(femur_coarse, femur_fine, 0.015 * femur_fine);
  EXPECT_NEAR(tibia_coarse, tibia_fine, 0.015 * tibia_fine);
  const auto [femur_free, tibia_free] = bound_areas(shape, 3.0, false);
  EXPECT_GT(std::abs(femur_free - femur_fine), 0.03 * femur_fine)
      << "the rims make no difference here: the test shows nothing";
}

TEST(Build, StageSubcommandRunsOnlyWhatItNeeds)
{
  const fs::path shape = fresh_folder("cyl_shape"), out = fresh_folder("cyl_distance");
  ASSERT_EQ(run_ligsim("synth cylinder --out " + shape.string()).exit_code, 0);
  ASSERT_EQ(run_ligsim("distance --surface " + (shape / "surface.stl").string() + " --out " +
                       out.string())
                .exit_code,
            0);
  EXPECT_TRUE(fs::exists(out / "distance.vti"));
  EXPECT_FALSE(fs::exists(out / "mesh.vtu"));
  EXPECT_EQ(statuses(read_summary(out)).size(), 2u); // voxelize, distance
}

TEST(Build, RealMclCompletesEveryStage)
{
  const fs::path out = fresh_folder("mcl");
  const CliResult result =
      run_ligsim("build --config " + source_path("data/vhf-right-knee/mcl.toml").string() +
                 " --out " + out.string());
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  expect_readable_outputs(out);
  const nlohmann::json summary = read_summary(out);
  EXPECT_EQ(statuses(summary).size(), 12u); // nine, and the companion's tetmesh, fibers, model
  const nlohmann::json& attachments = summary["stages"]["attachments"]["figures"];
  EXPECT_NE(attachments["tibia"]["rule"].get<std::string>().find("proximity"), std::string::npos);
  EXPECT_NE(attachments["femur"]["rule"].get<std::string>().find("end"), std::string::npos);
  EXPECT_EQ(attachments["tibia"]["vertices"].get<int>(), 412); // as the data's README states
  const nlohmann::json& mesh = summary["stages"]["tetmesh"]["figures"];
  EXPECT_GT(mesh["min_volume_mm3"].get<double>(), 0.0);
  EXPECT_GE(mesh["min_dihedral_deg"].get<double>(), 5.0);
  expect_centerline_inside_between_attachments(
      out, io::read_surface(source_path("data/vhf-right-knee/VHF_Right_Ligament_MCL_smooth.stl")),
      2.0);
}

namespace {

/// The shipped MCL with one defect of several kinds, as an OBJ: a duplicated triangle, a flipped
/// triangle, a hole (the fan of one vertex removed) and a stray octahedron 20 mm off.
fs::path write_defective_mcl(const std::string& name)
{
  TriangleSurface mcl =
      io::read_surface(source_path("data/vhf-right-knee/VHF_Right_Ligament_MCL_smooth.stl"));
  const int hole_centre = mcl.F(1500, 0);
  std::string obj;
  for (Eigen::Index v = 0; v < mcl.V.rows(); ++v)
    obj += fmt::format("v {} {} {}\n", mcl.V(v, 0), mcl.V(v, 1), mcl.V(v, 2));
  const Eigen::Vector3d centre = mcl.V.colwise().maxCoeff().transpose() + Eigen::Vector3d(20, 0, 0);
  for (int corner = 0; corner < 6; ++corner) {
    const Eigen::Vector3d p =
        centre + (corner % 2 ? -1.0 : 1.0) * Eigen::Vector3d::Unit(corner / 2);
    obj += fmt::format("v {} {} {}\n", p.x(), p.y(), p.z());
  }
  const auto face = [&obj](int a, int b, int c) {
    obj += fmt::format("f {} {} {}\n", a + 1, b + 1, c + 1);
  };
  for (Eigen::Index f = 0; f < mcl.F.rows(); ++f) {
    if ((mcl.F.row(f).array() == hole_centre).any())
      continue;
    if (f == 100)
      face(mcl.F(f, 0), mcl.F(f, 2), mcl.F(f, 1));
    else
      face(mcl.F(f, 0), mcl.F(f, 1), mcl.F(f, 2));
  }
  face(mcl.F(7, 0), mcl.F(7, 1), mcl.F(7, 2));
  const int o = static_cast<int>(mcl.V.rows());
  for (int sx = 0; sx < 2; ++sx)
    for (int sy = 0; sy < 2; ++sy)
      for (int sz = 0; sz < 2; ++sz) {
        if ((sx + sy + sz) % 2 == 1)
          face(o + sx, o + 4 + sz, o + 2 + sy);
        else
          face(o + sx, o + 2 + sy, o + 4 + sz);
      }
  const fs::path file = fs::temp_directory_path() / name;
  std::ofstream(file) << obj;
  return file;
}

} // namespace

TEST(Build, DefectiveMclIsRepairedIntoAValidModel)
{
  const fs::path surface = write_defective_mcl("ligsim_defective_mcl.obj");
  const fs::path out = fresh_folder("repaired_mcl");
  const CliResult result =
      run_ligsim("build --config " + source_path("data/vhf-right-knee/mcl.toml").string() +
                 " --surface " + surface.string() + " --out " + out.string());
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  for (const char* line :
       {"surface repair: removed duplicate triangles: 1",
        "surface repair: flipped inconsistent orientation: 1",
        "surface repair: removed stray components: 1", "surface repair: filled holes: 1"})
    EXPECT_NE(result.stderr_text.find(line), std::string::npos) << line << "\n"
                                                                << result.stderr_text;
  expect_readable_outputs(out);
  const nlohmann::json summary = read_summary(out);
  const nlohmann::json& repair = summary["results"]["surface_repair"];
  EXPECT_TRUE(repair["repaired"].get<bool>());
  EXPECT_EQ(repair["repairs"].size(), 4u);
  for (const auto& entry : repair["repairs"]) {
    EXPECT_EQ(entry["count"].get<int>(), 1) << entry.dump();
    EXPECT_EQ(entry["locations"].size(), 1u) << entry.dump();
  }
  const nlohmann::json& mesh = summary["stages"]["tetmesh"]["figures"];
  EXPECT_GT(mesh["min_volume_mm3"].get<double>(), 0.0);
  expect_centerline_inside_between_attachments(out, io::read_surface(out / "attachments.vtp"), 2.0);
}

TEST(Build, BonesBesideTheModelAreClosedOutwardShells)
{
  // The band's femur box inside out, one triangle missing, with a stray box 20 mm off.
  const fs::path shape = fresh_folder("bone_shape"), out = fresh_folder("bone_model");
  ASSERT_EQ(run_ligsim("synth band --out " + shape.string()).exit_code, 0);
  const TriangleSurface box = io::read_surface(shape / "femur.stl");
  std::string obj;
  for (Eigen::Index v = 0; v < box.V.rows(); ++v)
    obj += fmt::format("v {} {} {}\n", box.V(v, 0), box.V(v, 1), box.V(v, 2));
  const Eigen::Vector3d far = box.V.colwise().maxCoeff().transpose() + Eigen::Vector3d(20, 0, 0);
  for (Eigen::Index v = 0; v < box.V.rows(); ++v)
    obj += fmt::format("v {} {} {}\n", far.x() + 0.1 * (box.V(v, 0) - box.V(0, 0)),
                       far.y() + 0.1 * (box.V(v, 1) - box.V(0, 1)),
                       far.z() + 0.1 * (box.V(v, 2) - box.V(0, 2)));
  for (Eigen::Index f = 0; f < box.F.rows(); ++f) {
    if (f > 0)
      obj += fmt::format("f {} {} {}\n", box.F(f, 0) + 1, box.F(f, 2) + 1, box.F(f, 1) + 1);
    const Eigen::Index o = box.V.rows();
    obj +=
        fmt::format("f {} {} {}\n", box.F(f, 0) + o + 1, box.F(f, 1) + o + 1, box.F(f, 2) + o + 1);
  }
  std::ofstream(shape / "femur_defective.obj") << obj;
  const CliResult result =
      run_ligsim("build --surface " + (shape / "surface.stl").string() + " --femur " +
                 (shape / "femur_defective.obj").string() + " --tibia " +
                 (shape / "tibia.stl").string() + " --voxel 0.4 --out " + out.string());
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  for (const std::string& line :
       {std::string("femur repair: filled holes: 1"),
        std::string("femur repair: removed stray components: 1"),
        fmt::format("femur repair: flipped inward orientation: {}", box.F.rows())})
    EXPECT_NE(result.stderr_text.find(line), std::string::npos) << line << "\n"
                                                                << result.stderr_text;
  const nlohmann::json repairs = read_summary(out)["results"]["bone_repair"];
  EXPECT_TRUE(repairs["femur"]["repaired"].get<bool>()) << repairs.dump();
  EXPECT_FALSE(repairs["tibia"]["repaired"].get<bool>()) << repairs.dump();
  for (const char* bone : {"femur", "tibia"}) {
    const TriangleSurface written = io::from_polydata(read_vtp(out / (std::string(bone) + ".vtp")));
    EXPECT_TRUE(check_topology(written).closed_manifold()) << bone;
    EXPECT_EQ(written.F.rows(), io::read_surface(shape / (std::string(bone) + ".stl")).F.rows())
        << bone;
  }
  EXPECT_NEAR(signed_volume(io::from_polydata(read_vtp(out / "femur.vtp"))), signed_volume(box),
              1e-6 * signed_volume(box));
}

TEST(Build, LabelMapOfTheKneeBuildsAValidModel)
{
  // The shipped label map (0.3 x 0.3 x 1 mm voxels) made from the VHF surfaces, its labels
  // given by name (segment names in its header, and its colour table).
  const fs::path out = fresh_folder("mcl_labels");
  const CliResult result =
      run_ligsim("build --config " + source_path("data/vhf-right-knee/mcl_labels.toml").string() +
                 " --out " + out.string());
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  expect_readable_outputs(out);
  const nlohmann::json summary = read_summary(out);
  const nlohmann::json& labels = summary["results"]["label_map"];
  EXPECT_EQ(labels["spacing_mm"], nlohmann::json::array({0.3, 0.3, 1.0}));
  EXPECT_NE(labels["frame"].get<std::string>().find("LPS"), std::string::npos);
  EXPECT_GT(labels["wall_s"].get<double>(), 0.0);
  const std::map<std::string, std::pair<int, std::string>> parts = {
      {"ligament", {1, "labels_ligament.vtp"}},
      {"femur", {2, "femur.vtp"}},
      {"tibia", {3, "tibia.vtp"}}};
  for (const auto& [part, expected] : parts) {
    EXPECT_EQ(labels[part]["label"].get<int>(), expected.first) << part;
    EXPECT_EQ(labels[part]["names"].size(), 2u) << part; // header and colour table
    EXPECT_EQ(labels[part]["components"].get<int>(), 1) << part;
    EXPECT_TRUE(fs::exists(out / expected.second)) << part;
  }
  // The bones are written once, by the label step, under the names the flexion job reads.
  for (const char* stale : {"labels_femur.vtp", "labels_tibia.vtp"})
    EXPECT_FALSE(fs::exists(out / stale)) << stale;
  const nlohmann::json& mesh = summary["stages"]["tetmesh"]["figures"];
  EXPECT_GT(mesh["min_volume_mm3"].get<double>(), 0.0);
  // The smooth label surface keeps the segmented MCL's volume and lies on it, within a
  // fraction of the 1 mm slices. Measured: 777.6 of 776.2 mm^3; rms 0.097, max 0.35 mm.
  const TriangleSurface mcl =
      io::read_surface(source_path("data/vhf-right-knee/VHF_Right_Ligament_MCL_smooth.stl"));
  const TriangleSurface from_labels = io::read_surface(out / "labels_ligament.vtp");
  EXPECT_TRUE(check_topology(from_labels).closed_manifold());
  EXPECT_NEAR(std::abs(signed_volume(from_labels)), std::abs(signed_volume(mcl)),
              0.01 * std::abs(signed_volume(mcl)));
  const SurfaceQuery segmented(mcl);
  double squares = 0.0, farthest_mm = 0.0;
  for (Eigen::Index v = 0; v < from_labels.V.rows(); ++v) {
    const double d = segmented.distance(from_labels.V.row(v).transpose());
    squares += d * d;
    farthest_mm = std::max(farthest_mm, d);
  }
  EXPECT_LT(std::sqrt(squares / static_cast<double>(from_labels.V.rows())), 0.15);
  EXPECT_LT(farthest_mm, 0.5);
  expect_centerline_inside_between_attachments(out, from_labels, 2.0);
  // The bones' surfaces from their labels are closed (the image border closes them).
  for (const char* bone : {"femur.vtp", "tibia.vtp"}) {
    const TriangleSurface surface = io::read_surface(out / bone);
    EXPECT_TRUE(check_topology(surface).closed_manifold()) << bone;
    EXPECT_GT(signed_volume(surface), 0.0) << bone; // facing outward
  }

  // The flexion job finds the model's bones: the axis is fitted to the label map's cartilage,
  // and contact keeps the ligament out of both bones.
  const fs::path flexion = fresh_folder("mcl_labels_flexion");
  const CliResult flexed = run_ligsim(
      "flexion --config " + source_path("data/vhf-right-knee/flexion.toml").string() + " --model " +
      out.string() + " --angles 0,15 --no-images --out " + flexion.string());
  ASSERT_EQ(flexed.exit_code, 0) << flexed.stderr_text;
  const nlohmann::json swept = read_summary(flexion);
  EXPECT_GT(swept["parameters"]["axis"]["direction"][0].get<double>(), 0.95); // mediolateral
  const nlohmann::json angles = only_ligament(swept["results"])["angles"];
  ASSERT_EQ(angles.size(), 2u);
  for (const nlohmann::json& angle : angles) {
    EXPECT_TRUE(angle["converged"].get<bool>()) << angle.dump();
    for (const char* bone : {"femur", "tibia"})
      EXPECT_LT(angle["contact"][bone]["penetration_mm"].get<double>(), 0.05) << angle.dump();
  }
}
