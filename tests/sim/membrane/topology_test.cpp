#include "sim/membrane/mesh/topology.hpp"

#include "tests/sim/membrane/test_material.hpp"

#include "sim/membrane/crack/propagation.hpp"
#include "sim/membrane/crack/tearing.hpp"
#include "sim/membrane/mesh/generate.hpp"
#include "sim/membrane/model/corotational_elements.hpp"
#include "sim/membrane/model/implicit_euler.hpp"
#include "sim/membrane/scene/tear_metrics.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace ligsim::membrane {
namespace {

constexpr double kDegree = M_PI / 180.0;

double total_area(const MembraneMesh& mesh)
{
  double area = 0.0;
  for (int tri = 0; tri < mesh.triangle_count(); ++tri)
    area += rest_area(mesh, tri);
  return area;
}

/// True if p is inside the triangle (a, b, c), counter-clockwise, with a small tolerance.
bool inside(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c)
{
  const double eps = -1e-12;
  return cross(b - a, p - a) >= eps && cross(c - b, p - b) >= eps && cross(a - c, p - c) >= eps;
}

TEST(MembraneTopology, SplitSideKeepsTheAreaAndTheInheritedData)
{
  MembraneMesh mesh = rectangle_mesh(2.0, 2.0, 0.5, 0.0, 1);
  for (int tri = 0; tri < mesh.triangle_count(); ++tri)
    mesh.fiber_angle_rad[tri] = 0.01 * tri;
  const double area = total_area(mesh);
  // An interior side: the first side of some triangle that has an opposite.
  NodeIncidence incidence = build_incidence(mesh);
  SideRef side;
  for (int tri = 0; tri < mesh.triangle_count() && side.triangle < 0; ++tri)
    if (opposite_side(mesh, incidence, {tri, 0}))
      side = {tri, 0};
  const double parent_fiber = mesh.fiber_angle_rad[side.triangle];
  TopologyEdit edit;
  const int node = split_side(mesh, incidence, side, 0.4, edit);
  EXPECT_EQ(manifold_problem(mesh), "");
  EXPECT_NEAR(total_area(mesh), area, 1e-13);
  EXPECT_EQ(edit.triangles.size(), 4u);
  EXPECT_EQ(edit.new_nodes, std::vector<int>{node});
  EXPECT_DOUBLE_EQ(mesh.fiber_angle_rad[edit.triangles[1]], parent_fiber);
}

TEST(MembraneTopology, ACutAcrossTheSheetSeparatesIt)
{
  MembraneMesh mesh = rectangle_mesh(4.0, 4.0, 0.5, 0.1, 2);
  // A cut through the boundary: its points lie outside, it stops where it meets the boundary.
  const PolylineCut cut = cut_polyline(mesh, {{-2.0, 0.1}, {2.5, 0.1}}, {});
  EXPECT_EQ(manifold_problem(mesh), "");
  EXPECT_EQ(component_count(mesh), 2);
  EXPECT_EQ(cut.start_node, -1);
  EXPECT_EQ(cut.end_node, -1);
}

TEST(MembraneTopology, AnInteriorCutOpensWithTwoTips)
{
  MembraneMesh mesh = rectangle_mesh(4.0, 4.0, 0.4, 0.1, 3);
  const PolylineCut cut = cut_polyline(mesh, {{-1.0, 0.0}, {1.0, 0.0}}, {});
  EXPECT_EQ(manifold_problem(mesh), "");
  EXPECT_EQ(component_count(mesh), 1);
  ASSERT_GE(cut.start_node, 0);
  ASSERT_GE(cut.end_node, 0);
  EXPECT_LT(cut.start_direction.x(), -0.9);
  EXPECT_GT(cut.end_direction.x(), 0.9);
  // The nodes inside the cut were duplicated: the crack is open.
  for (std::size_t i = 0; i + 1 < cut.advances.size(); ++i) {
    int copies = 0;
    for (int v = 0; v < mesh.node_count(); ++v)
      copies += mesh.rest[v] == cut.advances[i].to_rest;
    EXPECT_EQ(copies, 2) << "cut node " << i;
  }
  EXPECT_GE(cut.advances.size(), 4u);
  const NodeIncidence incidence = build_incidence(mesh);
  EXPECT_TRUE(is_enclosed(mesh, incidence, cut.start_node));
  EXPECT_TRUE(is_enclosed(mesh, incidence, cut.end_node));
}

TEST(MembraneTopology, ManifoldCheckFindsBrokenMeshes)
{
  MembraneMesh mesh = rectangle_mesh(2.0, 2.0, 0.5, 0.0, 1);
  MembraneMesh doubled = mesh;
  doubled.add_triangle(doubled.triangles[3], 0.0, {false, false, false}, {0, 0, 0});
  EXPECT_NE(manifold_problem(doubled), "");
  MembraneMesh flipped = mesh;
  std::swap(flipped.triangles[2][0], flipped.triangles[2][1]);
  EXPECT_NE(manifold_problem(flipped), "");
  MembraneMesh lonely = mesh;
  lonely.add_node(Vec2(5.0, 5.0));
  EXPECT_NE(manifold_problem(lonely), "");
  MembraneMesh one_sided = mesh;
  NodeIncidence incidence = build_incidence(one_sided);
  for (int tri = 0; tri < one_sided.triangle_count(); ++tri)
    if (opposite_side(one_sided, incidence, {tri, 1})) {
      one_sided.side_cut[tri][1] = true;
      break;
    }
  EXPECT_NE(manifold_problem(one_sided), "");
}

/// 200 random crack advances (mode 2 with snapping) and initiations on a sheet with per-element
/// fibers, a fixed side and a loaded side: the mesh stays a valid manifold, the area and the mass
/// are conserved, no angle falls below the bound, every triangle keeps the fiber of the original
/// triangle it lies in, and the dynamics still run without NaN.
TEST(MembraneTopology, TwoHundredRandomSplitsKeepAValidMeshAndDynamics)
{
  std::mt19937 random(17);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), unit(0.0, 1.0);
  MembraneMesh mesh = rectangle_mesh(6.0, 6.0, 0.4, 0.15, 5);
  for (int tri = 0; tri < mesh.triangle_count(); ++tri)
    mesh.fiber_angle_rad[tri] = angle(random);
  const MembraneMesh original = mesh;
  for (int v = 0; v < mesh.node_count(); ++v)
    if (mesh.rest[v].x() < -2.99)
      mesh.constraint[v] = NodeConstraint::prescribed;
  const MembraneMaterial m = test::lens_like_material();
  const double areal_density = m.density_t_per_mm3 * m.thickness_mm;
  CorotationalElements elements(m);
  elements.rebuild(mesh);
  std::vector<int> all(mesh.node_count());
  for (int v = 0; v < mesh.node_count(); ++v)
    all[v] = v;
  update_lumped_masses(mesh, build_incidence(mesh), areal_density, all);
  const double area = total_area(mesh);
  const PropagationSettings settings; // mode 2, 10 degrees
  const double bound = std::min(settings.min_angle_rad, min_rest_angle(original));

  std::vector<CrackTip> tips;
  int splits = 0, advances = 0;
  while (advances < 200) {
    if (tips.empty() || unit(random) < 0.1) { // start a crack in a random untouched element
      const int tri =
          static_cast<int>(unit(random) * mesh.triangle_count()) % mesh.triangle_count();
      const auto started = initiate_crack(
          mesh, tri, Vec2(std::cos(angle(random)), std::sin(angle(random))), settings);
      for (const CrackAdvance& advance : started) {
        apply_edit(mesh, elements, advance.edit, areal_density);
        if (advance.continues)
          tips.push_back({advance.to, (advance.to_rest - advance.from_rest).normalized(), 0});
        splits += advance.split_face;
        ++advances;
      }
    } else {
      const std::size_t pick = static_cast<std::size_t>(unit(random) * tips.size()) % tips.size();
      CrackTip& tip = tips[pick];
      // A random direction within 60 degrees of the crack's way.
      const double turn = (2.0 * unit(random) - 1.0) * 60.0 * kDegree;
      const Vec2 d = Eigen::Rotation2Dd(turn) * tip.previous;
      const auto advance = advance_crack(mesh, tip.node, d, settings);
      if (advance) {
        apply_edit(mesh, elements, advance->edit, areal_density);
        splits += advance->split_face;
        ++advances;
      }
      if (advance && advance->continues)
        tip = {advance->to, (advance->to_rest - advance->from_rest).normalized(), 0};
      else
        tips.erase(tips.begin() + static_cast<long>(pick));
    }
    const NodeIncidence incidence = build_incidence(mesh);
    tips.erase(
        std::remove_if(tips.begin(), tips.end(),
                       [&](const CrackTip& t) { return !is_enclosed(mesh, incidence, t.node); }),
        tips.end());
    ASSERT_EQ(manifold_problem(mesh), "") << "after " << advances << " advances";
    ASSERT_NEAR(total_area(mesh), area, 1e-12 * area);
    ASSERT_GE(min_rest_angle(mesh), bound - 1e-12);
  }
  EXPECT_GT(splits, 50) << "most advances should split faces";
  EXPECT_GT(mesh.triangle_count(), original.triangle_count() + 100);

  double mass = 0.0;
  for (double node_mass : mesh.mass)
    mass += node_mass;
  EXPECT_NEAR(mass, areal_density * area, 1e-12 * areal_density * area);
  for (int tri = 0; tri < mesh.triangle_count(); ++tri) {
    const Triangle& t = mesh.triangles[tri];
    const Vec2 centre = (mesh.rest[t[0]] + mesh.rest[t[1]] + mesh.rest[t[2]]) / 3.0;
    for (int parent = 0; parent < original.triangle_count(); ++parent) {
      const Triangle& p = original.triangles[parent];
      if (inside(centre, original.rest[p[0]], original.rest[p[1]], original.rest[p[2]])) {
        ASSERT_DOUBLE_EQ(mesh.fiber_angle_rad[tri], original.fiber_angle_rad[parent]) << tri;
        break;
      }
    }
  }
  // The fixed side is the line x = -3: its nodes, their copies and the nodes split between
  // two of them are fixed; no other node is.
  for (int v = 0; v < mesh.node_count(); ++v)
    ASSERT_EQ(mesh.constraint[v] == NodeConstraint::prescribed, mesh.rest[v].x() < -3.0 + 1e-12)
        << "node " << v << " at x = " << mesh.rest[v].x();

  // Pull the right side for a while: the torn mesh still moves without NaN.
  SolverSettings solver;
  solver.time_step_s = 1e-3;
  solver.mass_damping_per_s = 50.0;
  ImplicitEuler euler(solver);
  std::vector<Vec2> forces(mesh.node_count(), Vec2::Zero());
  for (int v = 0; v < mesh.node_count(); ++v)
    if (mesh.rest[v].x() > 2.99)
      forces[v] = Vec2(0.002, 0.0005);
  for (int step = 0; step < 50; ++step)
    ASSERT_NO_THROW(euler.step(mesh, elements, forces));
  for (int v = 0; v < mesh.node_count(); ++v)
    ASSERT_TRUE(mesh.position[v].allFinite() && mesh.velocity[v].allFinite()) << v;
}

} // namespace
} // namespace ligsim::membrane
