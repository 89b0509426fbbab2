#include "sim/mesh/tet_shape.hpp"

#include "common/error.hpp"
#include "sim/mesh/element_nodes.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <cmath>

namespace ligsim::sim {

TetShape tet_shape(const TetCorners& P)
{
  Eigen::Matrix3d edges; // columns P1 - P0, P2 - P0, P3 - P0
  for (int k = 0; k < 3; ++k)
    edges.col(k) = (P.row(k + 1) - P.row(0)).transpose();
  TetShape shape;
  const double det = edges.determinant();
  shape.V0 = det / 6.0;
  // Barycentric coordinates: lambda_k = e_k^T edges^-1 (x - P0) for k = 1..3, and lambda_0 is
  // one minus their sum; their gradients are the rows of edges^-1.
  const Eigen::Matrix3d inverse = edges.inverse();
  for (int k = 0; k < 3; ++k)
    shape.D.row(k + 1) = inverse.row(k);
  shape.D.row(0) = -(inverse.row(0) + inverse.row(1) + inverse.row(2));
  return shape;
}

std::vector<TetShape> compute_rest_shapes(const TetMesh& mesh)
{
  check_element_nodes(mesh.V, mesh.T);
  std::vector<TetShape> shapes(static_cast<std::size_t>(mesh.T.rows()));
  for (Eigen::Index e = 0; e < mesh.T.rows(); ++e) {
    TetCorners P;
    for (int i = 0; i < 4; ++i)
      P.row(i) = mesh.V.row(mesh.T(e, i));
    double longest_edge = 0.0;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        longest_edge = std::max(longest_edge, (P.row(i) - P.row(j)).norm());
    TetShape shape = tet_shape(P);
    // A volume at round-off level of the element's own size has no usable shape vectors.
    const double degenerate_volume = 1e-12 * longest_edge * longest_edge * longest_edge;
    if (std::abs(shape.V0) <= degenerate_volume)
      fail("element {} (nodes {} {} {} {}) is degenerate: rest volume {:.3g} mm^3 for a longest "
           "edge of {:.3g} mm",
           e, mesh.T(e, 0), mesh.T(e, 1), mesh.T(e, 2), mesh.T(e, 3), shape.V0, longest_edge);
    if (shape.V0 < 0.0)
      fail("element {} (nodes {} {} {} {}) is inverted in the rest shape: volume {:.3g} mm^3 "
           "(expected positive orientation)",
           e, mesh.T(e, 0), mesh.T(e, 1), mesh.T(e, 2), mesh.T(e, 3), shape.V0);
    shapes[static_cast<std::size_t>(e)] = shape;
  }
  return shapes;
}

Eigen::Vector3d toward_opposite_face(const TetMesh& mesh, Eigen::Index e, int i,
                                     double volume_fraction)
{
  const Eigen::Vector3d p = mesh.V.row(mesh.T(e, i));
  const Eigen::Vector3d a = mesh.V.row(mesh.T(e, (i + 1) % 4));
  const Eigen::Vector3d b = mesh.V.row(mesh.T(e, (i + 2) % 4));
  const Eigen::Vector3d c = mesh.V.row(mesh.T(e, (i + 3) % 4));
  const Eigen::Vector3d normal = (b - a).cross(c - a).normalized();
  const double height = (p - a).dot(normal);
  return p - (1.0 - volume_fraction) * height * normal;
}

} // namespace ligsim::sim
