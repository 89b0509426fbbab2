/// `ligsim build --labels` end to end on a label map written by hand as 3D Slicer writes a
/// segmentation: anisotropic voxels (0.3 x 0.3 x 1 mm), a rotated direction matrix, an origin
/// far from zero and a cylinder oblique to the slices, named in the header. The model must come
/// out in the image's physical frame, on the analytic cylinder, with the centerline along its
/// axis.

#include "common/error.hpp"
#include "common/vtk_files.hpp"
#include "pipeline/stage_graph/label_inputs.hpp"
#include "stages/geometry/surface_topology.hpp"
#include "stages/io/vtk_convert.hpp"
#include "stages/labelmap/label_image.hpp"
#include "tests/pipeline/cli_runner.hpp"
#include "tests/stages/labelmap/oblique_shapes.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numeric>

using namespace ligsim;
using namespace ligsim::test;
namespace fs = std::filesystem;

namespace {

constexpr int kCylinderLabel = 6;

/// Writes `file` (NRRD, raw unsigned char, Slicer's segment keys naming the label) holding the
/// shape.
void write_slicer_nrrd(const ObliqueCylinder& shape, const fs::path& file)
{
  std::ofstream out(file, std::ios::binary);
  out.precision(17);
  const Eigen::Vector3i& dims = shape.dims;
  out << "NRRD0004\ntype: unsigned char\ndimension: 3\nspace: left-posterior-superior\n"
      << "sizes: " << dims.x() << ' ' << dims.y() << ' ' << dims.z() << "\nspace directions:";
  for (int c = 0; c < 3; ++c) {
    const Eigen::Vector3d column = shape.direction.col(c) * shape.spacing_mm[c];
    out << " (" << column.x() << ',' << column.y() << ',' << column.z() << ')';
  }
  const Eigen::Vector3d& origin = shape.origin_mm;
  out << "\nkinds: domain domain domain\nencoding: raw\n"
      << "space origin: (" << origin.x() << ',' << origin.y() << ',' << origin.z() << ")\n"
      << "Segment0_ID:=Segment_1\nSegment0_LabelValue:=" << kCylinderLabel
      << "\nSegment0_Layer:=0\nSegment0_Name:=Cylinder\n\n";
  for (int k = 0; k < dims.z(); ++k)
    for (int j = 0; j < dims.y(); ++j)
      for (int i = 0; i < dims.x(); ++i)
        out.put(test::voxel_inside(shape, i, j, k) ? static_cast<char>(kCylinderLabel) : 0);
}

} // namespace

TEST(BuildLabels, RotatedAnisotropicCylinderComesOutInThePhysicalFrame)
{
  const fs::path dir = fresh_folder("labels_cylinder_map"), out = fresh_folder("labels_cylinder");
  fs::create_directories(dir);
  const ObliqueCylinder cylinder;
  write_slicer_nrrd(cylinder, dir / "cylinder.seg.nrrd");
  // The label by its segment name, in another case; with no bones, the femur takes the +z end
  // and the tibia the -z end.
  const CliResult result =
      run_ligsim("build --labels " + (dir / "cylinder.seg.nrrd").string() +
                 " --ligament-label cylinder --voxel 0.3 --out " + out.string());
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  std::ifstream summary_file(out / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(summary_file);
  EXPECT_EQ(summary["results"]["label_map"]["ligament"]["label"].get<int>(), kCylinderLabel);

  // Every model node lies on or in the analytic cylinder within a fraction of the slice (1 mm),
  // and the tets' centroid is its centre. Measured: nodes out by at most 0.16 mm, centroid off
  // by 0.009 mm.
  const TetMesh model = io::from_unstructured_grid(read_vtu(out / "model.vtu"));
  ASSERT_GT(model.T.rows(), 100);
  double worst_mm = 0.0;
  for (Eigen::Index v = 0; v < model.V.rows(); ++v)
    worst_mm = std::max(worst_mm, cylinder.signed_distance(model.V.row(v).transpose()));
  EXPECT_LT(worst_mm, 0.3);
  Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();
  double tets_volume = 0.0;
  for (Eigen::Index t = 0; t < model.T.rows(); ++t) {
    const auto corner = [&](int c) { return Eigen::Vector3d(model.V.row(model.T(t, c))); };
    const double v =
        (corner(1) - corner(0)).dot((corner(2) - corner(0)).cross(corner(3) - corner(0))) / 6.0;
    tets_volume += v;
    first_moment += v * (corner(0) + corner(1) + corner(2) + corner(3)) / 4.0;
  }
  const Eigen::Vector3d centroid = first_moment / tets_volume;
  EXPECT_LT((centroid - cylinder.centre).norm(), 0.05);
  // The volume: the label surface keeps it within 2 % (its smoothed rims), and the mesher's
  // facets, chords of that surface within facet_distance of it, lose at most area x that.
  // Measured: 438.0 mm^3 of 452.4 (surface 453.1, facet distance 0.13 mm).
  const nlohmann::json& mesh = summary["stages"]["tetmesh"]["figures"];
  const double volume = mesh["total_volume_mm3"];
  EXPECT_NEAR(tets_volume, volume, 1e-6 * volume);
  const double facet_distance_mm = mesh["used"]["facet_distance_mm"];
  const double analytic_volume = cylinder.volume_mm3();
  EXPECT_LT(volume, 1.02 * analytic_volume);
  EXPECT_GT(volume, 0.98 * analytic_volume - cylinder.area_mm2() * facet_distance_mm);

  // The centerline runs along the cylinder's axis, near it, over most of its length. Measured:
  // 0.71 degrees, 0.27 mm, 16.2 mm.
  const Points line = io::points_of(read_vtp(out / "centerline.vtp"));
  ASSERT_GT(line.rows(), 10);
  const Eigen::Vector3d mean = line.colwise().mean().transpose();
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  double off_axis_mm = 0.0;
  for (Eigen::Index i = 0; i < line.rows(); ++i) {
    const Eigen::Vector3d d = line.row(i).transpose() - mean;
    scatter += d * d.transpose();
    const Eigen::Vector3d from_centre = line.row(i).transpose() - cylinder.centre;
    off_axis_mm = std::max(off_axis_mm,
                           (from_centre - from_centre.dot(cylinder.axis) * cylinder.axis).norm());
  }
  const Eigen::Vector3d line_axis =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(scatter).eigenvectors().col(2);
  EXPECT_GT(std::abs(line_axis.dot(cylinder.axis)), std::cos(2.0 * M_PI / 180.0));
  EXPECT_LT(off_axis_mm, 0.5);
  const double span_mm = (line.row(0) - line.row(line.rows() - 1)).norm();
  EXPECT_GT(span_mm, 0.8 * 2.0 * cylinder.half_length_mm);
  fs::remove_all(dir);
}

TEST(BuildLabels, BoneWithCornerTouchingBlobsComesOutAsOneShell)
{
  // A 10-voxel cube of bone (label 2) with two 2-voxel blobs touching it at a corner each: one
  // 26-connected component, but the contour gives the blobs shells of their own. The ligament
  // (label 1) is a block elsewhere.
  labelmap::LabelImage image;
  image.dims = {30, 30, 30};
  image.labels.assign(30 * 30 * 30, 0);
  const auto fill = [&](Eigen::Vector3i lo, Eigen::Vector3i hi, int label) {
    for (int k = lo.z(); k < hi.z(); ++k)
      for (int j = lo.y(); j < hi.y(); ++j)
        for (int i = lo.x(); i < hi.x(); ++i)
          image(i, j, k) = label;
  };
  fill({5, 5, 5}, {15, 15, 15}, 2);
  fill({15, 15, 15}, {17, 17, 17}, 2); // at the cube's corner voxel (14, 14, 14)
  fill({15, 3, 15}, {17, 5, 17}, 2);   // at its corner voxel (14, 5, 14)
  fill({20, 20, 5}, {27, 27, 12}, 1);
  const fs::path dir = fresh_folder("labels_shells");
  fs::create_directories(dir);
  labelmap::write_label_image(image, dir / "knee.nrrd");

  pipeline::BuildConfig config;
  config.labels = dir / "knee.nrrd";
  config.ligament_label = "1";
  config.tibia_label = "2";
  nlohmann::json report;
  const pipeline::BuildConfig result = pipeline::surfaces_from_labels(config, dir, report);
  const nlohmann::json& tibia = report["tibia"];
  EXPECT_EQ(tibia["components"].get<int>(), 1) << tibia.dump();
  EXPECT_EQ(tibia["shells"].get<int>(), 3) << tibia.dump();
  EXPECT_EQ(tibia["dropped_stray_shells"].get<int>(), 2) << tibia.dump();
  EXPECT_EQ(tibia["dropped_inner_cavities"].get<int>(), 0) << tibia.dump();

  // The written surface: one closed, outward shell about the cube's 1000 mm^3.
  const TriangleSurface surface = io::from_polydata(read_vtp(result.tibia));
  EXPECT_TRUE(check_topology(surface).closed_manifold());
  EXPECT_NEAR(signed_volume(surface), 1000.0, 50.0);
  std::vector<int> parent(static_cast<std::size_t>(surface.V.rows()));
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int v) {
    while (parent[static_cast<std::size_t>(v)] != v)
      v = parent[static_cast<std::size_t>(v)];
    return v;
  };
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f)
    for (int c = 1; c < 3; ++c)
      parent[static_cast<std::size_t>(root(surface.F(f, c)))] = root(surface.F(f, 0));
  int shells = 0;
  for (int v = 0; v < static_cast<int>(parent.size()); ++v)
    shells += root(v) == v ? 1 : 0;
  EXPECT_EQ(shells, 1);
}

TEST(BuildLabels, LigamentInPiecesIsRefusedAndAStrayVoxelIsDropped)
{
  // A ligament (label 1) as a 4 x 4 x 20 voxel bar, and a bone (label 2) elsewhere. A stray
  // voxel beside the bar is dropped; the bar cut in two halves by one empty slice is refused,
  // naming the ligament and its pieces, since its model would be a part of it.
  const auto map_with = [](bool cut) {
    labelmap::LabelImage image;
    image.dims = {20, 20, 30};
    image.labels.assign(20 * 20 * 30, 0);
    for (int k = 4; k < 24; ++k)
      for (int j = 4; j < 8; ++j)
        for (int i = 4; i < 8; ++i)
          image(i, j, k) = cut && k == 14 ? 0 : 1;
    image(12, 5, 10) = 1; // the stray voxel
    for (int k = 4; k < 14; ++k)
      for (int j = 12; j < 18; ++j)
        for (int i = 12; i < 18; ++i)
          image(i, j, k) = 2;
    return image;
  };
  const fs::path dir = fresh_folder("labels_pieces");
  fs::create_directories(dir);
  pipeline::BuildConfig config;
  config.labels = dir / "knee.nrrd";
  config.ligament_label = "1";
  config.tibia_label = "2";
  nlohmann::json report;

  labelmap::write_label_image(map_with(false), config.labels);
  pipeline::surfaces_from_labels(config, dir, report);
  EXPECT_EQ(report["ligament"]["components"].get<int>(), 2) << report["ligament"].dump();
  EXPECT_EQ(report["ligament"]["dropped_voxels"].get<int>(), 1) << report["ligament"].dump();

  labelmap::write_label_image(map_with(true), config.labels);
  try {
    pipeline::surfaces_from_labels(config, dir, report);
    ADD_FAILURE() << "a ligament in two halves was taken";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("ligament: label 1 is in 3 pieces"), std::string::npos) << message;
    EXPECT_NE(message.find("holds 160 of its 305 voxels (52 %)"), std::string::npos) << message;
    EXPECT_NE(message.find("finer spacing"), std::string::npos) << message;
  }
  fs::remove_all(dir);
}
