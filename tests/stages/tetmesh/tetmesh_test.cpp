#include "common/error.hpp"
#include "common/tet_faces.hpp"
#include "stages/geometry/surface_topology.hpp"
#include "stages/io/surface_reader.hpp"
#include "stages/tetmesh/tetmesh.hpp"
#include "tests/stages/tetmesh/test_surfaces.hpp"

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <vector>

namespace ligsim::tetmesh {
namespace {

using ::testing::HasSubstr;

const double pi = std::acos(-1.0);
constexpr double capsule_radius = 3, capsule_length = 20; // mm
const double capsule_volume = pi * capsule_radius * capsule_radius * capsule_length +
                              4.0 / 3.0 * pi * std::pow(capsule_radius, 3);
const double capsule_area =
    2 * pi * capsule_radius * capsule_length + 4 * pi * capsule_radius * capsule_radius;

TriangleSurface mcl()
{
  return io::read_surface(std::string(LIGSIM_SOURCE_DIR) +
                          "/data/vhf-right-knee/VHF_Right_Ligament_MCL_smooth.stl");
}

/// Checks computed here, independently of measure_quality: indices in range, every vertex
/// used by a tet (compact), every tet positively oriented. Returns the total volume, mm^3.
double expect_valid_and_compact(const TetMesh& mesh)
{
  std::vector<char> used(static_cast<std::size_t>(mesh.V.rows()), 0);
  double total = 0;
  int non_positive = 0;
  for (Eigen::Index t = 0; t < mesh.T.rows(); ++t) {
    for (int k = 0; k < 4; ++k) {
      EXPECT_GE(mesh.T(t, k), 0);
      EXPECT_LT(mesh.T(t, k), mesh.V.rows());
      used[static_cast<std::size_t>(mesh.T(t, k))] = 1;
    }
    const Eigen::Vector3d v0 = mesh.V.row(mesh.T(t, 0)), v1 = mesh.V.row(mesh.T(t, 1)),
                          v2 = mesh.V.row(mesh.T(t, 2)), v3 = mesh.V.row(mesh.T(t, 3));
    const double six_volume = (v1 - v0).dot((v2 - v0).cross(v3 - v0));
    non_positive += six_volume <= 0;
    total += six_volume / 6;
  }
  EXPECT_EQ(non_positive, 0) << "tets with non-positive volume";
  EXPECT_EQ(std::count(used.begin(), used.end(), 0), 0) << "vertices used by no tet";
  return total;
}

void print_figures(const std::string& label, const Result& result, double seconds)
{
  const Quality& q = result.quality;
  std::cout << fmt::format(
      "[{}] cell {:.3f} facet {:.3f} distance {:.3f} mm: {} tets, {} nodes, dihedral "
      "{:.2f}..{:.2f} "
      "deg, worst radius-edge {:.3f}, volume {:.2f} of {:.2f} mm^3, facet circumcentre / centroid "
      "distance {:.3f} / {:.3f} mm, {:.2f} s\n",
      label, result.used.cell_size_mm, result.used.facet_size_mm, result.used.facet_distance_mm,
      q.tets, q.nodes, q.min_dihedral_deg, q.max_dihedral_deg, q.worst_radius_edge_ratio,
      q.total_volume_mm3, q.surface_volume_mm3, q.max_facet_circumcentre_distance_mm,
      q.max_facet_centroid_distance_mm, seconds);
}

Result timed_mesh(const std::string& label, const TriangleSurface& surface, const Parameters& p)
{
  const auto start = std::chrono::steady_clock::now();
  Result result = make_tet_mesh(surface, p);
  print_figures(label, result,
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return result;
}

TEST(Tetmesh, TestCapsuleIsClosedWithNearlyAnalyticVolumeAndArea)
{
  const TriangleSurface surface = test::capsule(capsule_radius, capsule_length, 64);
  EXPECT_TRUE(check_topology(surface).closed_manifold());
  // An inscribed polyhedron: a little less than the analytic values (0.3 % at 64 segments).
  EXPECT_NEAR(signed_volume(surface), capsule_volume, 0.005 * capsule_volume);
  EXPECT_LT(signed_volume(surface), capsule_volume);
  EXPECT_NEAR(surface_area(surface), capsule_area, 0.005 * capsule_area);
}

TEST(Tetmesh, CapsuleVolumeSurfaceAndAngles)
{
  const TriangleSurface surface = test::capsule(capsule_radius, capsule_length, 64);
  Parameters p;
  p.cell_size_mm = 1.0;
  p.facet_size_mm = 1.0;
  p.facet_distance_mm = 0.05;
  const Result result = timed_mesh("capsule", surface, p);
  const Quality& q = result.quality;

  EXPECT_EQ(result.used.cell_size_mm, 1.0);
  EXPECT_EQ(result.used.facet_distance_mm, 0.05);
  EXPECT_EQ(q.tets, result.mesh.T.rows());
  EXPECT_EQ(q.nodes, result.mesh.V.rows());
  const double volume = expect_valid_and_compact(result.mesh);
  EXPECT_NEAR(q.total_volume_mm3, volume, 1e-9 * volume);
  EXPECT_GT(q.min_volume_mm3, 0);

  // Boundary vertices lie on the input surface; the tet mesh of a convex shape lies inside it;
  // Mesh_3 bounds each surface facet's circumcentre within facet_distance of the surface.
  EXPECT_LE(q.max_surface_distance_mm, 1e-6);
  EXPECT_LE(q.total_volume_mm3, q.surface_volume_mm3 * (1 + 1e-12));
  EXPECT_LE(q.max_facet_circumcentre_distance_mm, p.facet_distance_mm * (1 + 1e-9));
  EXPECT_NEAR(q.total_volume_mm3, capsule_volume, 0.02 * capsule_volume);

  EXPECT_GE(q.min_dihedral_deg, 5.0);
  EXPECT_LE(q.max_dihedral_deg, 175.0);
}

TEST(Tetmesh, DefaultSizesFollowTheThicknessRule)
{
  const TriangleSurface surface = test::capsule(capsule_radius, capsule_length, 64);
  const double thickness = 2 * capsule_volume / capsule_area; // analytic: 2.77 mm
  const Parameters resolved = default_sizes(surface, Parameters{});
  EXPECT_NEAR(resolved.cell_size_mm, thickness / 2, 0.01 * thickness / 2);
  EXPECT_NEAR(resolved.facet_size_mm, thickness / 2, 0.01 * thickness / 2);
  EXPECT_NEAR(resolved.facet_distance_mm, thickness / 20, 0.01 * thickness / 20);

  Parameters partly;
  partly.facet_size_mm = 0.8;
  EXPECT_EQ(default_sizes(surface, partly).facet_size_mm, 0.8); // given sizes are kept

  // 10-node tets default to 1.7 times the thickness, the surface held as close as linear tets'.
  Parameters quadratic;
  quadratic.order = 2;
  const Parameters coarse = default_sizes(surface, quadratic);
  EXPECT_NEAR(coarse.cell_size_mm, 1.7 * thickness, 0.01 * 1.7 * thickness);
  EXPECT_NEAR(coarse.facet_size_mm, 1.7 * thickness, 0.01 * 1.7 * thickness);
  EXPECT_EQ(coarse.facet_distance_mm, resolved.facet_distance_mm);
}

TEST(Tetmesh, SameSeedSameMeshOtherSeedOtherMesh)
{
  const TriangleSurface surface = test::capsule(capsule_radius, capsule_length, 48);
  const Result first = make_tet_mesh(surface, Parameters{});
  const Result second = make_tet_mesh(surface, Parameters{});
  ASSERT_EQ(first.mesh.T.rows(), second.mesh.T.rows());
  ASSERT_EQ(first.mesh.V.rows(), second.mesh.V.rows());
  EXPECT_TRUE(first.mesh.T == second.mesh.T);
  EXPECT_TRUE(first.mesh.V == second.mesh.V);
  expect_valid_and_compact(first.mesh);

  // The seed reaches CGAL: another seed places the initial surface points elsewhere.
  Parameters reseeded;
  reseeded.seed = 1;
  const Result other = make_tet_mesh(surface, reseeded);
  expect_valid_and_compact(other.mesh);
  EXPECT_FALSE(other.mesh.V.rows() == first.mesh.V.rows() && other.mesh.V == first.mesh.V);
  EXPECT_GE(other.quality.min_dihedral_deg, 5.0);
}

TEST(Tetmesh, PerturbationAndExudationRemoveSlivers)
{
  const TriangleSurface surface = test::capsule(capsule_radius, capsule_length, 48);
  Parameters raw;
  raw.perturb = false;
  raw.exude_slivers = false;
  const Result unoptimised = make_tet_mesh(surface, raw);
  const Result optimised = make_tet_mesh(surface, Parameters{});
  expect_valid_and_compact(unoptimised.mesh);
  // Delaunay refinement alone leaves slivers (dihedral angles near 0 and 180 degrees).
  EXPECT_LT(unoptimised.quality.min_dihedral_deg, 5.0);
  EXPECT_GE(optimised.quality.min_dihedral_deg, 5.0);
}

TEST(Tetmesh, RealMclWithDefaults)
{
  const TriangleSurface surface = mcl();
  ASSERT_EQ(surface.F.rows(), 3110);
  const Result result = timed_mesh("MCL", surface, Parameters{});
  const Quality& q = result.quality;

  expect_valid_and_compact(result.mesh);
  EXPECT_GT(q.min_volume_mm3, 0);
  EXPECT_GE(q.min_dihedral_deg, 5.0);
  EXPECT_LE(q.max_surface_distance_mm, result.used.facet_distance_mm);
  EXPECT_LE(q.max_facet_circumcentre_distance_mm, result.used.facet_distance_mm * (1 + 1e-9));
  // Facets cut the band's rounded rims a little: the volume is within 3 % of the input's.
  EXPECT_NEAR(q.total_volume_mm3, q.surface_volume_mm3, 0.03 * q.surface_volume_mm3);
  EXPECT_GT(q.tets, 1000); // 1.5 mm thick band meshed at about half its thickness
}

/// The boundary faces of `mesh` with corners on both sides of the plane x = `x_mm` (farther than
/// 0.01 mm from it).
int faces_across(const TetMesh& mesh, double x_mm)
{
  int across = 0;
  for (const auto& face : tet_boundary_faces(mesh.T)) {
    double low = x_mm, high = x_mm;
    for (int v : face) {
      low = std::min(low, mesh.V(v, 0));
      high = std::max(high, mesh.V(v, 0));
    }
    across += low < x_mm - 0.01 && high > x_mm + 0.01;
  }
  return across;
}

TEST(Tetmesh, AFeatureLineBecomesAChainOfMeshEdges)
{
  // A circle around the capsule's middle, on its surface (0.004 mm off the facets between the
  // 64 vertices of a ring), as a footprint's rim: no boundary face of the mesh crosses it.
  const TriangleSurface surface = test::capsule(capsule_radius, capsule_length, 64);
  const double middle = 0.5 * capsule_length;
  FeatureLine circle;
  for (int k = 0; k <= 128; ++k) {
    const double angle = 2 * pi * (k % 128) / 128;
    circle.emplace_back(middle, capsule_radius * std::cos(angle), capsule_radius * std::sin(angle));
  }
  const Result plain = make_tet_mesh(surface, Parameters{});
  EXPECT_GT(faces_across(plain.mesh, middle), 0) << "a mesh that ignores the circle crosses it";
  const Result kept = make_tet_mesh(surface, Parameters{}, {circle});
  expect_valid_and_compact(kept.mesh);
  EXPECT_EQ(faces_across(kept.mesh, middle), 0);
  EXPECT_GE(kept.quality.min_dihedral_deg, 5.0);
}

TEST(Tetmesh, AFeatureLineNeedsTwoFinitePoints)
{
  const TriangleSurface surface = test::capsule(capsule_radius, capsule_length, 16);
  for (const FeatureLine& bad :
       {FeatureLine{Eigen::Vector3d(1, 0, 0)},
        FeatureLine{Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(NAN, 0, 0)}}) {
    try {
      make_tet_mesh(surface, Parameters{}, {bad});
      ADD_FAILURE() << "no error";
    } catch (const InputError& error) {
      EXPECT_THAT(error.what(), HasSubstr("feature line 0"));
    }
  }
}

/// The message of the InputError that make_tet_mesh throws, or "" if none.
std::string rejection(const TriangleSurface& surface, const Parameters& p = {})
{
  try {
    make_tet_mesh(surface, p);
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(Tetmesh, BadSurfaceIsAClearInputError)
{
  EXPECT_THAT(rejection(TriangleSurface{}), HasSubstr("surface is empty"));

  TriangleSurface open = test::capsule(capsule_radius, capsule_length, 32);
  open.F.conservativeResize(open.F.rows() - 1, 3);
  EXPECT_THAT(rejection(open), HasSubstr("surface is not closed: 3 boundary edges"));

  TriangleSurface flipped = test::capsule(capsule_radius, capsule_length, 32);
  std::swap(flipped.F(10, 1), flipped.F(10, 2));
  EXPECT_THAT(rejection(flipped), HasSubstr("not consistently oriented: 3 edges"));

  TriangleSurface nan = test::capsule(capsule_radius, capsule_length, 32);
  nan.V(7, 1) = std::nan("");
  EXPECT_THAT(rejection(nan), HasSubstr("vertex 7 has a non-finite coordinate"));

  TriangleSurface out_of_range = test::capsule(capsule_radius, capsule_length, 32);
  out_of_range.F(4, 2) = static_cast<int>(out_of_range.V.rows());
  EXPECT_THAT(rejection(out_of_range), HasSubstr("triangle 4 has vertex index"));
}

TEST(Tetmesh, BadParametersAreAClearInputError)
{
  const TriangleSurface closed = test::capsule(capsule_radius, capsule_length, 32);
  Parameters steep;
  steep.facet_angle_deg = 40;
  EXPECT_THAT(rejection(closed, steep), HasSubstr("facet_angle_deg"));
  Parameters loose;
  loose.radius_edge_ratio = 1;
  EXPECT_THAT(rejection(closed, loose), HasSubstr("radius_edge_ratio"));
  Parameters nan_size;
  nan_size.cell_size_mm = std::nan("");
  EXPECT_THAT(rejection(closed, nan_size), HasSubstr("cell_size_mm must be finite"));
  Parameters negative_seed;
  negative_seed.seed = -1;
  EXPECT_THAT(rejection(closed, negative_seed), HasSubstr("seed"));
}

} // namespace
} // namespace ligsim::tetmesh
