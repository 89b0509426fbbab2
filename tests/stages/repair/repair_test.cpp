// One test per defect kind: each is injected into the real MCL (data/vhf-right-knee), which the
// repair must bring back to a closed, consistently oriented manifold of the same volume, with
// the defect reported at the place it was injected.

#include "stages/geometry/surface_topology.hpp"
#include "stages/io/surface_reader.hpp"
#include "stages/repair/repair.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <filesystem>

using namespace ligsim;
namespace fs = std::filesystem;

namespace {

TriangleSurface read_mcl()
{
  TriangleSurface mcl = io::read_surface(fs::path(LIGSIM_SOURCE_DIR) /
                                         "data/vhf-right-knee/VHF_Right_Ligament_MCL_smooth.stl");
  io::orient_outward(mcl);
  return mcl;
}

const TriangleSurface& mcl()
{
  static const TriangleSurface surface = read_mcl();
  return surface;
}

int add_vertex(TriangleSurface& s, const Eigen::Vector3d& p)
{
  s.V.conservativeResize(s.V.rows() + 1, 3);
  s.V.row(s.V.rows() - 1) = p.transpose();
  return static_cast<int>(s.V.rows() - 1);
}

void add_triangle(TriangleSurface& s, int a, int b, int c)
{
  s.F.conservativeResize(s.F.rows() + 1, 3);
  s.F.row(s.F.rows() - 1) << a, b, c;
}

Eigen::Vector3d vertex(const TriangleSurface& s, int v)
{
  return s.V.row(v).transpose();
}

Eigen::Vector3d outward_normal(const TriangleSurface& s, int f)
{
  const Eigen::Vector3d a = vertex(s, s.F(f, 0)), b = vertex(s, s.F(f, 1)),
                        c = vertex(s, s.F(f, 2));
  return (b - a).cross(c - a).normalized();
}

/// A closed tetrahedron on four vertices, outward for a positive (b-a).((c-a)x(d-a)).
void add_tetrahedron(TriangleSurface& s, int a, int b, int c, int d)
{
  add_triangle(s, a, c, b);
  add_triangle(s, a, b, d);
  add_triangle(s, b, c, d);
  add_triangle(s, a, d, c);
}

/// Repairs `damaged`, expects one repair of `kind` with `count`, and a result that is a closed
/// manifold with the MCL's volume. Returns the repair for location checks.
repair::Repair expect_repaired(const TriangleSurface& damaged, const std::string& kind, int count)
{
  const repair::Result result = repair::repair_surface(damaged);
  const repair::Repair* found = result.report.find(kind);
  EXPECT_NE(found, nullptr) << kind << " not reported";
  if (found == nullptr)
    return {};
  EXPECT_EQ(found->count, count);
  EXPECT_FALSE(found->locations.empty());
  const TopologyReport topology = check_topology(result.surface);
  EXPECT_TRUE(topology.closed_manifold());
  EXPECT_EQ(topology.degenerate_triangles, 0);
  EXPECT_NEAR(std::abs(signed_volume(result.surface)), signed_volume(mcl()),
              2e-3 * signed_volume(mcl()));
  EXPECT_EQ(result.source_vertex.size(), static_cast<std::size_t>(result.surface.V.rows()));
  return *found;
}

} // namespace

TEST(Repair, SoundSurfaceIsLeftAlone)
{
  const repair::Result result = repair::repair_surface(mcl());
  EXPECT_TRUE(result.report.empty());
  EXPECT_EQ(result.surface.F, mcl().F);
  EXPECT_EQ(result.surface.V, mcl().V);
}

TEST(Repair, DegenerateTrianglesAreRemoved)
{
  TriangleSurface s = mcl();
  const int a = s.F(10, 0), b = s.F(10, 1);
  add_triangle(s, a, a, b);                                         // repeated vertex
  const int m = add_vertex(s, 0.5 * (vertex(s, a) + vertex(s, b))); // zero area
  add_triangle(s, a, b, m);
  const repair::Repair r = expect_repaired(s, "degenerate_triangles", 2);
  EXPECT_EQ(r.locations.front().vertices, (std::vector<int>{a, a, b}));
}

TEST(Repair, DuplicateTrianglesAreRemoved)
{
  TriangleSurface s = mcl();
  add_triangle(s, s.F(7, 0), s.F(7, 1), s.F(7, 2));
  add_triangle(s, s.F(9, 0), s.F(9, 2), s.F(9, 1)); // the same triangle, the other way
  expect_repaired(s, "duplicate_triangles", 2);
}

TEST(Repair, FlippedTrianglesAreTurned)
{
  TriangleSurface s = mcl();
  s.F.row(100) = Eigen::RowVector3i(s.F(100, 0), s.F(100, 2), s.F(100, 1));
  s.F.row(2000) = Eigen::RowVector3i(s.F(2000, 0), s.F(2000, 2), s.F(2000, 1));
  const repair::Repair r = expect_repaired(s, "inconsistent_orientation", 2);
  const Eigen::Vector3d centre =
      (vertex(s, s.F(100, 0)) + vertex(s, s.F(100, 1)) + vertex(s, s.F(100, 2))) / 3.0;
  EXPECT_LT((r.locations.front().point_mm - centre).norm(), 1e-12);
}

TEST(Repair, NonManifoldEdgeIsSplitAndItsPieceRemoved)
{
  // A small tetrahedron hung on one MCL edge: that edge then has four triangles.
  TriangleSurface s = mcl();
  const int f = 500, u = s.F(f, 0), v = s.F(f, 1);
  const Eigen::Vector3d n = outward_normal(s, f), mid = 0.5 * (vertex(s, u) + vertex(s, v));
  const Eigen::Vector3d along = (vertex(s, v) - vertex(s, u)).normalized();
  const int w = add_vertex(s, mid + 0.5 * n + 0.3 * n.cross(along));
  const int x = add_vertex(s, mid + 0.5 * n - 0.3 * n.cross(along));
  const Eigen::Vector3d e1 = vertex(s, v) - vertex(s, u), e2 = vertex(s, w) - vertex(s, u),
                        e3 = vertex(s, x) - vertex(s, u);
  if (e1.dot(e2.cross(e3)) > 0)
    add_tetrahedron(s, u, v, w, x);
  else
    add_tetrahedron(s, u, v, x, w);
  const repair::Repair r = expect_repaired(s, "non_manifold_edges", 1);
  ASSERT_EQ(r.locations.front().vertices.size(), 2u);
  EXPECT_EQ(std::min(u, v), r.locations.front().vertices[0]);
  EXPECT_EQ(std::max(u, v), r.locations.front().vertices[1]);
  EXPECT_EQ(r.locations.front().vertex_points_mm[0], vertex(s, std::min(u, v)));
  const repair::Result result = repair::repair_surface(s);
  EXPECT_EQ(result.report.find("stray_components")->count, 1);
  EXPECT_EQ(result.surface.F.rows(), mcl().F.rows());
}

TEST(Repair, NonManifoldVertexIsSplitAndItsPieceRemoved)
{
  // A small tetrahedron touching the MCL at one vertex only.
  TriangleSurface s = mcl();
  const int f = 800, u = s.F(f, 0);
  const Eigen::Vector3d n = outward_normal(s, f), p = vertex(s, u);
  const Eigen::Vector3d t = n.unitOrthogonal(), b = n.cross(t);
  const int w = add_vertex(s, p + 0.6 * n + 0.3 * t);
  const int x = add_vertex(s, p + 0.6 * n - 0.15 * t + 0.26 * b);
  const int y = add_vertex(s, p + 0.6 * n - 0.15 * t - 0.26 * b);
  const Eigen::Vector3d e1 = vertex(s, w) - p, e2 = vertex(s, x) - p, e3 = vertex(s, y) - p;
  if (e1.dot(e2.cross(e3)) > 0)
    add_tetrahedron(s, u, w, x, y);
  else
    add_tetrahedron(s, u, w, y, x);
  const repair::Repair r = expect_repaired(s, "non_manifold_vertices", 1);
  EXPECT_EQ(r.locations.front().vertices, std::vector<int>{u});
  EXPECT_EQ(repair::repair_surface(s).surface.F.rows(), mcl().F.rows());
}

TEST(Repair, StrayPieceIsRemoved)
{
  // An octahedron of 8 faces, 20 mm off the ligament, as in a Slicer export.
  TriangleSurface s = mcl();
  const Eigen::Vector3d centre = s.V.colwise().maxCoeff().transpose() + Eigen::Vector3d(20, 0, 0);
  int c[6];
  for (int axis = 0; axis < 3; ++axis)
    for (int sign = 0; sign < 2; ++sign)
      c[2 * axis + sign] =
          add_vertex(s, centre + (sign ? -1.0 : 1.0) * Eigen::Vector3d::Unit(axis));
  // Faces (+x/-x) x (+y/-y) x (+z/-z), oriented outward.
  for (int sx = 0; sx < 2; ++sx)
    for (int sy = 0; sy < 2; ++sy)
      for (int sz = 0; sz < 2; ++sz) {
        const bool odd = (sx + sy + sz) % 2 == 1;
        if (odd)
          add_triangle(s, c[sx], c[4 + sz], c[2 + sy]);
        else
          add_triangle(s, c[sx], c[2 + sy], c[4 + sz]);
      }
  const repair::Repair r = expect_repaired(s, "stray_components", 1);
  EXPECT_LT((r.locations.front().point_mm - centre).norm(), 1e-9);
}

TEST(Repair, SmallHoleIsFilled)
{
  // The fan of triangles around one vertex removed: a hole of about 6 edges.
  TriangleSurface s = mcl();
  const int centre = s.F(1500, 0);
  TriangleSurface holed;
  holed.V = s.V;
  for (Eigen::Index f = 0; f < s.F.rows(); ++f)
    if ((s.F.row(f).array() != centre).all())
      add_triangle(holed, s.F(f, 0), s.F(f, 1), s.F(f, 2));
  ASSERT_LT(holed.F.rows(), s.F.rows());
  const repair::Repair r = expect_repaired(holed, "holes", 1);
  EXPECT_LT((r.locations.front().point_mm - vertex(s, centre)).norm(), 1.0);
}

TEST(Repair, BigHoleIsLeftForTheClosedCheck)
{
  // Half of a box removed: no piece of it is small, so nothing is filled.
  TriangleSurface s = mcl();
  TriangleSurface open;
  open.V = s.V;
  const double mid_z = 0.5 * (s.V.col(2).minCoeff() + s.V.col(2).maxCoeff());
  for (Eigen::Index f = 0; f < s.F.rows(); ++f)
    if (s.V(s.F(f, 0), 2) < mid_z)
      add_triangle(open, s.F(f, 0), s.F(f, 1), s.F(f, 2));
  const repair::Result result = repair::repair_surface(open);
  EXPECT_EQ(result.report.find("holes"), nullptr);
  EXPECT_GT(check_topology(result.surface).boundary_edges, 0);
}
