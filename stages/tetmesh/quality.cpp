#include "common/error.hpp"
#include "common/tet_faces.hpp"
#include "stages/geometry/surface_query.hpp"
#include "stages/geometry/surface_topology.hpp"
#include "stages/tetmesh/tet_geometry.hpp"
#include "stages/tetmesh/tetmesh.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <vector>

namespace ligsim::tetmesh {

Quality measure_quality(const TetMesh& mesh, const TriangleSurface& surface)
{
  Quality quality;
  quality.tets = static_cast<int>(mesh.T.rows());
  quality.nodes = static_cast<int>(mesh.V.rows());
  quality.surface_volume_mm3 = std::abs(ligsim::signed_volume(surface));
  if (mesh.T.rows() == 0)
    fail("cannot measure the quality of a mesh without tetrahedra");

  quality.min_dihedral_deg = std::numeric_limits<double>::infinity();
  quality.min_volume_mm3 = std::numeric_limits<double>::infinity();
  for (Eigen::Index t = 0; t < mesh.T.rows(); ++t) {
    std::array<Eigen::Vector3d, 4> v;
    for (int k = 0; k < 4; ++k)
      v[k] = mesh.V.row(mesh.T(t, k));
    const double volume = signed_tet_volume(v[0], v[1], v[2], v[3]);
    quality.min_volume_mm3 = std::min(quality.min_volume_mm3, volume);
    quality.total_volume_mm3 += volume;
    for (const double angle : dihedral_angles_deg(v)) {
      quality.min_dihedral_deg = std::min(quality.min_dihedral_deg, angle);
      quality.max_dihedral_deg = std::max(quality.max_dihedral_deg, angle);
    }
    quality.worst_radius_edge_ratio =
        std::max(quality.worst_radius_edge_ratio, radius_edge_ratio(v));
  }

  // One distance query for all points: boundary vertices, then facet centroids, then facet
  // circumcentres.
  const auto faces = tet_boundary_faces(mesh.T);
  const auto face_count = static_cast<Eigen::Index>(faces.size());
  std::vector<char> on_boundary(static_cast<std::size_t>(mesh.V.rows()), 0);
  for (const auto& face : faces)
    for (const int vertex : face)
      on_boundary[static_cast<std::size_t>(vertex)] = 1;
  const auto vertex_count =
      static_cast<Eigen::Index>(std::count(on_boundary.begin(), on_boundary.end(), 1));
  Points queries(vertex_count + 2 * face_count, 3);
  for (Eigen::Index v = 0, row = 0; v < mesh.V.rows(); ++v)
    if (on_boundary[static_cast<std::size_t>(v)])
      queries.row(row++) = mesh.V.row(v);
  for (Eigen::Index f = 0; f < face_count; ++f) {
    const auto& face = faces[static_cast<std::size_t>(f)];
    const Eigen::Vector3d a = mesh.V.row(face[0]), b = mesh.V.row(face[1]), c = mesh.V.row(face[2]);
    queries.row(vertex_count + f) = (a + b + c).transpose() / 3.0;
    queries.row(vertex_count + face_count + f) = triangle_circumcentre(a, b, c).transpose();
  }
  const SurfaceQuery query(surface);
  Eigen::VectorXd distances(queries.rows());
  for (Eigen::Index q = 0; q < queries.rows(); ++q)
    distances(q) = query.distance(queries.row(q).transpose());
  quality.max_surface_distance_mm = distances.head(vertex_count).maxCoeff();
  quality.max_facet_centroid_distance_mm = distances.segment(vertex_count, face_count).maxCoeff();
  quality.max_facet_circumcentre_distance_mm = distances.tail(face_count).maxCoeff();
  return quality;
}

} // namespace ligsim::tetmesh
