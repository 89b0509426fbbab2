#include "sim/contact/contact_surface.hpp"
#include "sim/mesh/quadratic_tet.hpp"
#include "sim/mesh/structured_mesh.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <set>

using namespace ligsim;
using namespace ligsim::sim;

namespace {

/// Area, and volume by the divergence theorem (positive when the faces face outward).
std::pair<double, double> area_and_volume(const ligsim::Points& V, const ligsim::Triangles& F)
{
  double area = 0.0;
  double volume = 0.0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)).transpose();
    const Eigen::Vector3d b = V.row(F(f, 1)).transpose();
    const Eigen::Vector3d c = V.row(F(f, 2)).transpose();
    area += 0.5 * (b - a).cross(c - a).norm();
    volume += a.dot(b.cross(c)) / 6.0;
  }
  return {area, volume};
}

} // namespace

TEST(ContactSurface, AQuadraticMeshsFacesAreSplitAtTheirMidEdgeNodes)
{
  const ligsim::TetMesh linear = structured_box_mesh({2, 2, 3}, {2.0, 2.0, 3.0});
  const QuadraticTetMesh quadratic = promote_to_quadratic(linear);
  const ligsim::TetMesh corners{quadratic.V, linear.T};
  const ContactSurface coarse = boundary_surface(linear);
  const ContactSurface split = boundary_surface(corners, &quadratic.T);

  EXPECT_EQ(split.faces.rows(), 4 * coarse.faces.rows());
  const auto [area, volume] = area_and_volume(quadratic.V, split.faces);
  EXPECT_NEAR(area, 2 * (4.0 + 6.0 + 6.0), 1e-12);
  EXPECT_NEAR(volume, 12.0, 1e-12); // outward, closed
  EXPECT_NEAR(split.areas_mm2.sum(), area, 1e-12);

  // Every node on the box's surface, corner or mid-edge, carries contact.
  std::set<int> on_surface;
  for (Eigen::Index n = 0; n < quadratic.V.rows(); ++n) {
    const Eigen::RowVector3d p = quadratic.V.row(n);
    if (p.minCoeff() < 1e-9 || p(0) > 2 - 1e-9 || p(1) > 2 - 1e-9 || p(2) > 3 - 1e-9)
      on_surface.insert(static_cast<int>(n));
  }
  EXPECT_EQ(std::set<int>(split.nodes.begin(), split.nodes.end()), on_surface);
  EXPECT_GT(split.nodes.size(), coarse.nodes.size());
}
