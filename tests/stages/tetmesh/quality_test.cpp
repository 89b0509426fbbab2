#include "stages/tetmesh/tetmesh.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace ligsim::tetmesh {
namespace {

const double pi = std::acos(-1.0);
double degrees(double radians)
{
  return radians * 180.0 / pi;
}

TetMesh single_tet(const Eigen::Matrix<double, 4, 3, Eigen::RowMajor>& corners)
{
  TetMesh mesh;
  mesh.V = corners;
  mesh.T.resize(1, 4);
  mesh.T << 0, 1, 2, 3;
  return mesh;
}

/// The four faces of the tet in `mesh`, facing outwards.
TriangleSurface tet_boundary(const TetMesh& mesh)
{
  TriangleSurface surface;
  surface.V = mesh.V;
  surface.F.resize(4, 3);
  surface.F << 1, 2, 3, 0, 3, 2, 0, 1, 3, 0, 2, 1;
  return surface;
}

/// Closed box [lo, hi]^3, 12 outward triangles.
TriangleSurface cube(double lo, double hi)
{
  TriangleSurface surface;
  surface.V.resize(8, 3);
  for (int i = 0; i < 8; ++i)
    surface.V.row(i) << (i & 1 ? hi : lo), (i & 2 ? hi : lo), (i & 4 ? hi : lo);
  surface.F.resize(12, 3);
  surface.F << 0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2,
      4, 6, 1, 3, 5, 3, 7, 5;
  return surface;
}

TEST(TetmeshQuality, RegularTetHasKnownAnglesRatioAndVolume)
{
  Eigen::Matrix<double, 4, 3, Eigen::RowMajor> corners;
  corners << 1, 1, 1, 1, -1, -1, -1, -1, 1, -1, 1, -1; // edge 2 sqrt(2), positive order
  const TetMesh mesh = single_tet(corners);
  const Quality q = measure_quality(mesh, tet_boundary(mesh));

  EXPECT_EQ(q.tets, 1);
  EXPECT_EQ(q.nodes, 4);
  EXPECT_NEAR(q.min_dihedral_deg, degrees(std::acos(1.0 / 3.0)), 1e-9); // 70.53 degrees
  EXPECT_NEAR(q.max_dihedral_deg, degrees(std::acos(1.0 / 3.0)), 1e-9);
  EXPECT_NEAR(q.worst_radius_edge_ratio, std::sqrt(6.0) / 4.0, 1e-12);
  EXPECT_NEAR(q.min_volume_mm3, 8.0 / 3.0, 1e-12);
  EXPECT_NEAR(q.total_volume_mm3, 8.0 / 3.0, 1e-12);
  EXPECT_NEAR(q.surface_volume_mm3, 8.0 / 3.0, 1e-12);
  EXPECT_NEAR(q.max_surface_distance_mm, 0.0, 1e-12);
  EXPECT_NEAR(q.max_facet_centroid_distance_mm, 0.0, 1e-12);
}

TEST(TetmeshQuality, CornerTetHasRightAndObliqueDihedralAngles)
{
  Eigen::Matrix<double, 4, 3, Eigen::RowMajor> corners;
  corners << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  const TetMesh mesh = single_tet(corners);
  const Quality q = measure_quality(mesh, tet_boundary(mesh));

  // Edges on the axes: 90 degrees; edges of the oblique face: acos(1/sqrt(3)) = 54.74 degrees.
  EXPECT_NEAR(q.min_dihedral_deg, degrees(std::acos(1.0 / std::sqrt(3.0))), 1e-9);
  EXPECT_NEAR(q.max_dihedral_deg, 90.0, 1e-9);
  // Circumcentre (1/2, 1/2, 1/2), shortest edge 1.
  EXPECT_NEAR(q.worst_radius_edge_ratio, std::sqrt(3.0) / 2.0, 1e-12);
  EXPECT_NEAR(q.total_volume_mm3, 1.0 / 6.0, 1e-12);
}

TEST(TetmeshQuality, InvertedTetHasNegativeVolume)
{
  Eigen::Matrix<double, 4, 3, Eigen::RowMajor> corners;
  corners << 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1; // first two axes swapped
  const TetMesh mesh = single_tet(corners);
  EXPECT_NEAR(measure_quality(mesh, tet_boundary(mesh)).min_volume_mm3, -1.0 / 6.0, 1e-12);
}

TEST(TetmeshQuality, DistancesAreMeasuredToTheGivenSurface)
{
  Eigen::Matrix<double, 4, 3, Eigen::RowMajor> corners;
  corners << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  const Quality q = measure_quality(single_tet(corners), cube(-1, 2));
  // Every corner is 1 mm from the box [-1, 2]^3; the centroid (1/3, 1/3, 1/3) of the oblique
  // face is 4/3 mm from it.
  EXPECT_NEAR(q.max_surface_distance_mm, 1.0, 1e-12);
  EXPECT_NEAR(q.max_facet_centroid_distance_mm, 4.0 / 3.0, 1e-12);
  EXPECT_NEAR(q.surface_volume_mm3, 27.0, 1e-12);
}

TEST(TetmeshQuality, InteriorFacesAreNotBoundary)
{
  // Two corner tets glued on the face (0,0,0)-(1,0,0)-(0,1,0), apexes at z = +1 and z = -1.
  TetMesh mesh;
  mesh.V.resize(5, 3);
  mesh.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1;
  mesh.T.resize(2, 4);
  mesh.T << 0, 1, 2, 3, 0, 2, 1, 4;
  // The "surface" is two tiny triangles at the apexes. Every boundary face holds an apex;
  // the farthest boundary centroid, (1/3, 1/3, +-1/3), is sqrt(6)/3 = 0.816 mm from it,
  // while the shared interior face's centroid (1/3, 1/3, 0) is sqrt(11)/3 = 1.106 mm away.
  const double tiny = 1e-7;
  TriangleSurface apexes;
  apexes.V.resize(6, 3);
  apexes.V << 0, 0, 1, tiny, 0, 1, 0, tiny, 1, 0, 0, -1, tiny, 0, -1, 0, tiny, -1;
  apexes.F.resize(2, 3);
  apexes.F << 0, 1, 2, 3, 4, 5;
  const Quality q = measure_quality(mesh, apexes);
  EXPECT_EQ(q.tets, 2);
  EXPECT_NEAR(q.total_volume_mm3, 1.0 / 3.0, 1e-12);
  EXPECT_NEAR(q.max_facet_centroid_distance_mm, std::sqrt(6.0) / 3.0, 1e-6);
  EXPECT_NEAR(q.max_surface_distance_mm, std::sqrt(2.0), 1e-6); // (1,0,0) or (0,1,0) to an apex
}

} // namespace
} // namespace ligsim::tetmesh
