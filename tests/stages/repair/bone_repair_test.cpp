// Bone repair: a bone becomes one closed, outward surface. Synthetic boxes with one defect of
// each kind (exact volumes and counts), and the HRA femurs, whose distal condyle region is open.

#include "common/error.hpp"
#include "stages/geometry/surface_query.hpp"
#include "stages/geometry/surface_topology.hpp"
#include "stages/io/surface_reader.hpp"
#include "stages/repair/repair.hpp"
#include "stages/synthetic/shapes.hpp"

#include <gtest/gtest.h>

#include <filesystem>

using namespace ligsim;
namespace fs = std::filesystem;

namespace {

/// `surface` with `more` appended (vertices renumbered).
TriangleSurface joined(const TriangleSurface& surface, const TriangleSurface& more)
{
  TriangleSurface all = surface;
  all.V.conservativeResize(surface.V.rows() + more.V.rows(), 3);
  all.V.bottomRows(more.V.rows()) = more.V;
  all.F.conservativeResize(surface.F.rows() + more.F.rows(), 3);
  all.F.bottomRows(more.F.rows()) = more.F.array() + static_cast<int>(surface.V.rows());
  return all;
}

const repair::Repair& found(const repair::Result& result, const std::string& kind)
{
  const repair::Repair* repair = result.report.find(kind);
  if (repair == nullptr)
    throw std::runtime_error("no repair of kind " + kind);
  return *repair;
}

const fs::path hra = fs::path(LIGSIM_SOURCE_DIR) / "data/hra-knee";

} // namespace

TEST(BoneRepair, CavityStrayPieceAndHoleLeaveOneClosedOutwardShell)
{
  // A 10 mm box missing one triangle (half of a face, 50 mm^2), a 2 mm box inside it (a cavity,
  // facing inward as a segmentation's inner surface does) and a 1 mm box 20 mm away.
  TriangleSurface outer = synthetic::box({0, 0, 0}, {10, 10, 10});
  const Eigen::Vector3i missing = outer.F.row(0);
  outer.F.row(0) = outer.F.row(outer.F.rows() - 1);
  outer.F.conservativeResize(outer.F.rows() - 1, 3);
  TriangleSurface cavity = synthetic::box({4, 4, 4}, {6, 6, 6});
  cavity.F.col(1).swap(cavity.F.col(2));
  const TriangleSurface bone =
      joined(joined(outer, cavity), synthetic::box({30, 0, 0}, {31, 1, 1}));

  const repair::Result result = repair::repair_bone(bone, "bone");
  EXPECT_TRUE(check_topology(result.surface).closed_manifold());
  EXPECT_NEAR(signed_volume(result.surface), 1000.0, 1e-9);
  const repair::Repair& holes = found(result, "holes");
  EXPECT_EQ(holes.count, 1);
  EXPECT_NEAR(holes.area_mm2, 50.0, 1e-9);
  EXPECT_GE(holes.triangles, 1);
  const Eigen::Vector3d a = outer.V.row(missing[0]), b = outer.V.row(missing[1]),
                        c = outer.V.row(missing[2]);
  EXPECT_NEAR((holes.locations.front().point_mm - (a + b + c) / 3.0).norm(), 0.0, 1e-9);
  const repair::Repair& cavities = found(result, "inner_cavities");
  EXPECT_EQ(cavities.count, 1);
  EXPECT_EQ(cavities.triangles, 12);
  EXPECT_NEAR(cavities.area_mm2, 24.0, 1e-9);
  EXPECT_NEAR((cavities.locations.front().point_mm - Eigen::Vector3d(5, 5, 5)).norm(), 0.0, 1.0);
  const repair::Repair& strays = found(result, "stray_components");
  EXPECT_EQ(strays.count, 1);
  EXPECT_EQ(strays.triangles, 12);
  EXPECT_EQ(result.report.find("inward_orientation"), nullptr);
}

TEST(BoneRepair, InwardSurfaceIsTurnedAndSplitVerticesMerged)
{
  // Every triangle of the box with its own three vertices, all facing inward.
  const TriangleSurface box = synthetic::box({0, 0, 0}, {2, 3, 4});
  TriangleSurface soup;
  soup.V.resize(3 * box.F.rows(), 3);
  soup.F.resize(box.F.rows(), 3);
  for (Eigen::Index f = 0; f < box.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      soup.V.row(3 * f + k) = box.V.row(box.F(f, 2 - k));
      soup.F(f, k) = static_cast<int>(3 * f + k);
    }
  const repair::Result result = repair::repair_bone(soup, "bone");
  EXPECT_EQ(found(result, "duplicate_vertices").count, 3 * 12 - 8);
  EXPECT_EQ(found(result, "inward_orientation").count, 12);
  EXPECT_EQ(result.surface.V.rows(), 8);
  EXPECT_TRUE(check_topology(result.surface).closed_manifold());
  EXPECT_NEAR(signed_volume(result.surface), 24.0, 1e-9);
}

TEST(BoneRepair, SoundBoneIsLeftAlone)
{
  const TriangleSurface tibia = io::read_surface(hra / "VH_F_Knee_L.glb#VH_F_tibia_L");
  const repair::Result result = repair::repair_bone(tibia, "tibia");
  EXPECT_TRUE(result.report.empty());
  EXPECT_EQ(result.surface.F, tibia.F);
}

TEST(BoneRepair, HraFemursComeOutClosedWithTheirCondylesFilled)
{
  struct Case {
    const char* femur;
    int open_edges; // as data/hra-knee/README.md says
    std::vector<const char*> condyles;
    double mean_below_mm; // the fair patch under the inferior condyle patches, mean
  };
  for (const Case& c :
       {Case{"VH_F_Knee_L.glb#VH_F_femur_L",
             120,
             {"VH_F_medial_condyle_of_left_femur_inf", "VH_F_lateral_condyle_of_femur_inf_L"},
             3.0},
        Case{"VH_M_Knee_R.glb#VH_M_femur_R",
             134,
             {"VH_M_medial_condyle_of_right_femur_inf", "VH_M_lateral_condyle_of_femur_inf_R"},
             4.5}}) {
    const TriangleSurface femur = io::read_surface(hra / c.femur);
    EXPECT_EQ(check_topology(femur).boundary_edges, c.open_edges) << c.femur;
    const repair::Result result = repair::repair_bone(femur, c.femur);
    const TopologyReport after = check_topology(result.surface);
    EXPECT_EQ(after.boundary_edges, 0) << c.femur;
    EXPECT_TRUE(after.closed_manifold()) << c.femur;
    EXPECT_GT(signed_volume(result.surface), 0.0) << c.femur;
    // Three holes: two small ones and the distal articular region (several thousand mm^2).
    const repair::Repair& holes = found(result, "holes");
    EXPECT_EQ(holes.count, 3) << c.femur;
    double largest = 0.0;
    for (const repair::Location& hole : holes.locations)
      largest = std::max(largest, hole.area_mm2);
    EXPECT_GT(largest, 5000.0) << c.femur;
    EXPECT_EQ(result.surface.F.rows(), femur.F.rows() + holes.triangles) << c.femur;
    // The patch follows the condyles the file models as separate sheets: a minimal (not fair)
    // patch lies 4.4 to 6 mm under them.
    const SurfaceQuery filled(result.surface);
    const std::string file = (hra / c.femur).string();
    for (const char* condyle : c.condyles) {
      const TriangleSurface patch =
          io::read_surface(file.substr(0, file.find('#')) + "#" + condyle);
      double mean = 0.0;
      for (Eigen::Index v = 0; v < patch.V.rows(); ++v)
        mean += filled.distance(patch.V.row(v).transpose()) / static_cast<double>(patch.V.rows());
      EXPECT_LT(mean, c.mean_below_mm) << condyle;
    }
  }
}
