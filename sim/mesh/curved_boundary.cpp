#include "sim/mesh/curved_boundary.hpp"

#include "common/tet_faces.hpp"
#include "sim/mesh/quadratic_tet.hpp"
#include "stages/geometry/surface_query.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <utility>
#include <vector>

namespace ligsim::sim {

namespace {

/// The mid-edge node of each boundary edge, in index order.
std::vector<int> boundary_mid_nodes(const QuadraticTetMesh& mesh)
{
  std::set<std::pair<int, int>> boundary_edges;
  const Tetrahedra corners = mesh.T.leftCols<4>();
  for (const auto& face : tet_boundary_faces(corners))
    for (int k = 0; k < 3; ++k)
      boundary_edges.insert(std::minmax(face[static_cast<std::size_t>(k)],
                                        face[static_cast<std::size_t>((k + 1) % 3)]));
  std::set<int> nodes;
  for (Eigen::Index e = 0; e < mesh.T.rows(); ++e)
    for (int k = 0; k < 6; ++k) {
      const auto [i, j] = kQuadraticTetEdges[static_cast<std::size_t>(k)];
      if (boundary_edges.count(std::minmax(mesh.T(e, i), mesh.T(e, j))))
        nodes.insert(mesh.T(e, 4 + k));
    }
  return {nodes.begin(), nodes.end()};
}

} // namespace

CurvedBoundary curve_boundary_to_surface(QuadraticTetMesh& mesh, const TriangleSurface& surface)
{
  std::vector<std::vector<Eigen::Index>> elements_of(static_cast<std::size_t>(mesh.V.rows()));
  for (Eigen::Index e = 0; e < mesh.T.rows(); ++e)
    for (int k = 4; k < 10; ++k)
      elements_of[static_cast<std::size_t>(mesh.T(e, k))].push_back(e);
  const QuadratureRule rule = tet_quadrature(5);
  const Eigen::Map<const Eigen::VectorXd> flat(mesh.V.data(), mesh.V.size());
  const auto worst_ratio = [&](int node) {
    double worst = INFINITY;
    for (Eigen::Index e : elements_of[static_cast<std::size_t>(node)])
      worst = std::min(worst, jacobian_ratio(quadratic_tet_nodes(mesh.T, e, flat), rule));
    return worst;
  };

  const SurfaceQuery query(surface);
  CurvedBoundary report;
  const std::vector<int> nodes = boundary_mid_nodes(mesh);
  report.boundary_mid_nodes = static_cast<int>(nodes.size());
  for (int node : nodes) {
    const Eigen::RowVector3d middle = mesh.V.row(node);
    const Eigen::RowVector3d offset = query.closest(middle.transpose()).point.transpose() - middle;
    double share = 1.0;
    double ratio = 0.0;
    for (int halving = 0; halving <= 4; ++halving, share *= 0.5) {
      mesh.V.row(node) = middle + share * offset;
      ratio = worst_ratio(node);
      if (ratio >= kMinCurvedJacobianRatio)
        break;
    }
    if (ratio < kMinCurvedJacobianRatio) { // no share of the offset keeps its elements sound
      share = 0.0;
      mesh.V.row(node) = middle;
      ratio = worst_ratio(node);
    }
    if (share == 1.0)
      ++report.moved;
    else if (share > 0.0)
      ++report.moved_part_way;
    else
      ++report.left_straight;
    report.max_offset_mm = std::max(report.max_offset_mm, share * offset.norm());
    report.max_gap_mm = std::max(report.max_gap_mm, (1.0 - share) * offset.norm());
    report.min_jacobian_ratio = std::min(report.min_jacobian_ratio, ratio);
  }
  return report;
}

} // namespace ligsim::sim
