/// The surface of 10-node tets laid onto the surface they were meshed from: a ball.

#include "sim/mesh/curved_boundary.hpp"
#include "sim/mesh/quadratic_tet.hpp"
#include "sim/mesh/sphere_surface.hpp"
#include "stages/tetmesh/tetmesh.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

using namespace ligsim;
using namespace ligsim::sim;

namespace {

constexpr double kRadius = 5.0;

double volume_of(const QuadraticTetMesh& mesh)
{
  double volume = 0.0;
  for (const QuadraticTetShape& shape : compute_rest_shapes(mesh, tet_quadrature(5)))
    volume += shape.V0;
  return volume;
}

} // namespace

TEST(CurvedBoundary, MidEdgeNodesGoOntoTheBallAndItsVolumeComesCloser)
{
  const TriangleSurface ball = sphere_surface(Eigen::Vector3d::Zero(), kRadius, 4);
  tetmesh::Parameters sizes;
  sizes.cell_size_mm = sizes.facet_size_mm = 2.0;
  const TetMesh linear = tetmesh::make_tet_mesh(ball, sizes).mesh;
  QuadraticTetMesh mesh = promote_to_quadratic(linear);
  const QuadraticTetMesh straight = mesh;
  const CurvedBoundary report = curve_boundary_to_surface(mesh, ball);

  ASSERT_GT(report.boundary_mid_nodes, 50);
  EXPECT_EQ(report.moved + report.moved_part_way + report.left_straight, report.boundary_mid_nodes);
  // A ball of round tets: every node goes the whole way, by up to the facets' sag.
  EXPECT_EQ(report.moved, report.boundary_mid_nodes);
  EXPECT_GT(report.max_offset_mm, 0.05);
  EXPECT_GE(report.min_jacobian_ratio, kMinCurvedJacobianRatio);
  int on_ball = 0, moved_inside = 0;
  for (Eigen::Index n = linear.V.rows(); n < mesh.V.rows(); ++n) {
    const double offset = (mesh.V.row(n) - straight.V.row(n)).norm();
    if (offset == 0.0)
      continue;
    // The faceted ball's surface lies within its sag of the true sphere (4 levels: 0.01 mm).
    on_ball += std::abs(mesh.V.row(n).norm() - kRadius) < 0.02;
    ++moved_inside;
  }
  EXPECT_EQ(on_ball, report.boundary_mid_nodes);
  EXPECT_EQ(moved_inside, report.boundary_mid_nodes); // interior mid-edge nodes stay put

  // The straight mesh misses the caps over its facets; the curved one holds nearly all of them.
  const double exact = 4.0 / 3.0 * M_PI * std::pow(kRadius, 3);
  const double straight_error = std::abs(volume_of(straight) - exact) / exact;
  const double curved_error = std::abs(volume_of(mesh) - exact) / exact;
  EXPECT_GT(straight_error, 0.01);
  EXPECT_LT(curved_error, 0.2 * straight_error);
}

TEST(CurvedBoundary, AMoveThatWouldFoldAnElementIsHeldBack)
{
  // One tet, its face (0, 1, 2) on the boundary, and a "surface" far across the element: the
  // full move would fold it, so every mid-edge node of that face stays nearer its edge.
  TetMesh tet;
  tet.V.resize(4, 3);
  tet.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  tet.T.resize(1, 4);
  tet.T << 0, 1, 2, 3;
  QuadraticTetMesh mesh = promote_to_quadratic(tet);
  TriangleSurface far_plane;
  far_plane.V.resize(3, 3);
  far_plane.V << -50, -50, 3, 50, -50, 3, 0, 50, 3;
  far_plane.F.resize(1, 3);
  far_plane.F << 0, 1, 2;
  const CurvedBoundary report = curve_boundary_to_surface(mesh, far_plane);
  EXPECT_EQ(report.boundary_mid_nodes, 6);
  EXPECT_LT(report.moved, 6);
  EXPECT_GT(report.max_gap_mm, 1.0);
  EXPECT_GE(report.min_jacobian_ratio, kMinCurvedJacobianRatio);
  EXPECT_GE(jacobian_ratio(
                quadratic_tet_nodes(
                    mesh.T, 0, Eigen::Map<const Eigen::VectorXd>(mesh.V.data(), mesh.V.size())),
                tet_quadrature(5)),
            kMinCurvedJacobianRatio);
}
