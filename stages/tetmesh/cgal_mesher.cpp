#include "stages/tetmesh/cgal_mesher.hpp"

#include "common/error.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Polyhedral_mesh_domain_with_features_3.h>
#include <CGAL/Random.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/exude_mesh_3.h>
#include <CGAL/make_mesh_3.h>
#include <CGAL/perturb_mesh_3.h>
#include <CGAL/refine_mesh_3.h>

#include <unordered_map>
#include <vector>

namespace ligsim::tetmesh {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Domain = CGAL::Polyhedral_mesh_domain_with_features_3<Kernel, SurfaceMesh>;
// Sequential: the parallel mesher's result depends on thread scheduling, not only on the seed.
using Triangulation = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using Complex = CGAL::Mesh_complex_3_in_triangulation_3<Triangulation>;
using Criteria = CGAL::Mesh_criteria_3<Triangulation>;

SurfaceMesh to_surface_mesh(const TriangleSurface& surface)
{
  SurfaceMesh mesh;
  std::vector<SurfaceMesh::Vertex_index> vertices;
  vertices.reserve(static_cast<std::size_t>(surface.V.rows()));
  for (Eigen::Index v = 0; v < surface.V.rows(); ++v)
    vertices.push_back(mesh.add_vertex({surface.V(v, 0), surface.V(v, 1), surface.V(v, 2)}));
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f) {
    const auto face = mesh.add_face(vertices[surface.F(f, 0)], vertices[surface.F(f, 1)],
                                    vertices[surface.F(f, 2)]);
    // Edges were checked already; what remains is a vertex where two sheets touch.
    if (face == SurfaceMesh::null_face())
      fail(
          "surface is non-manifold at a vertex of triangle {} ({}, {}, {}): two sheets touch there",
          f, surface.F(f, 0), surface.F(f, 1), surface.F(f, 2));
  }
  return mesh;
}

TetMesh to_tet_mesh(const Complex& complex)
{
  std::unordered_map<Triangulation::Vertex_handle, int> index_of;
  std::vector<Eigen::Vector3d> positions;
  std::vector<Eigen::Vector4i> tets;
  tets.reserve(complex.number_of_cells_in_complex());
  for (auto cell = complex.cells_in_complex_begin(); cell != complex.cells_in_complex_end();
       ++cell) {
    Eigen::Vector4i tet;
    for (int k = 0; k < 4; ++k) {
      const auto vertex = cell->vertex(k);
      const auto [found, inserted] = index_of.emplace(vertex, static_cast<int>(positions.size()));
      if (inserted) {
        const auto& p = vertex->point().point();
        positions.emplace_back(p.x(), p.y(), p.z());
      }
      tet(k) = found->second;
    }
    tets.push_back(tet);
  }

  TetMesh mesh;
  mesh.V.resize(static_cast<Eigen::Index>(positions.size()), 3);
  for (std::size_t v = 0; v < positions.size(); ++v)
    mesh.V.row(static_cast<Eigen::Index>(v)) = positions[v].transpose();
  mesh.T.resize(static_cast<Eigen::Index>(tets.size()), 4);
  for (std::size_t t = 0; t < tets.size(); ++t)
    mesh.T.row(static_cast<Eigen::Index>(t)) = tets[t].transpose();
  return mesh;
}

} // namespace

TetMesh mesh_with_cgal(const TriangleSurface& surface, const std::vector<FeatureLine>& features,
                       double feature_edge_mm, const Parameters& resolved)
{
  namespace params = CGAL::parameters;
  const SurfaceMesh boundary = to_surface_mesh(surface);
  CGAL::Random random(static_cast<unsigned int>(resolved.seed));
  Domain domain(boundary, &random);
  std::vector<std::vector<Kernel::Point_3>> lines;
  for (const FeatureLine& feature : features) {
    lines.emplace_back();
    for (const Eigen::Vector3d& p : feature)
      lines.back().emplace_back(p.x(), p.y(), p.z());
  }
  domain.add_features(lines.begin(), lines.end());
  const Criteria criteria(params::edge_size = feature_edge_mm,
                          params::facet_angle = resolved.facet_angle_deg,
                          params::facet_size = resolved.facet_size_mm,
                          params::facet_distance = resolved.facet_distance_mm,
                          params::cell_radius_edge_ratio = resolved.radius_edge_ratio,
                          params::cell_size = resolved.cell_size_mm);

  Complex complex =
      CGAL::make_mesh_3<Complex>(domain, criteria, params::no_perturb(), params::no_exude());
  // Perturbation moves vertices, which can break the facet size and distance criteria on the
  // surface (facet circumcentres up to 1.7x the facet distance on the MCL), so a refinement
  // follows each perturbation to restore every criterion. The vertices it adds can make new
  // slivers; another round perturbs those. Stop when a refinement adds nothing (two rounds
  // on the samples). Exudation changes weights only, never vertices or surface facets, so the
  // criteria hold on the output. No time limits: they would make the mesh machine-dependent.
  if (resolved.perturb) {
    constexpr int max_rounds = 3;
    for (int round = 0; round < max_rounds; ++round) {
      CGAL::perturb_mesh_3(complex, domain, params::time_limit = 0);
      const auto vertices_before = complex.triangulation().number_of_vertices();
      CGAL::refine_mesh_3(complex, domain, criteria, params::no_perturb(), params::no_exude());
      if (complex.triangulation().number_of_vertices() == vertices_before)
        break;
    }
  }
  if (resolved.exude_slivers)
    CGAL::exude_mesh_3(complex, params::time_limit = 0);
  return to_tet_mesh(complex);
}

} // namespace ligsim::tetmesh
