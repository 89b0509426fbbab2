#include "stages/tetmesh/tetmesh.hpp"

#include "common/error.hpp"
#include "stages/geometry/surface_topology.hpp"
#include "stages/io/surface_reader.hpp"
#include "stages/tetmesh/cgal_mesher.hpp"
#include "stages/tetmesh/tet_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace ligsim::tetmesh {
namespace {

void check_parameters(const Parameters& p)
{
  // Mesh_3 guarantees termination for facet angles up to 30 degrees and radius-edge
  // ratios from 2 up (smaller values may refine forever).
  if (!(p.facet_angle_deg > 0 && p.facet_angle_deg <= 30))
    fail("tetmesh: facet_angle_deg must be in (0, 30] degrees, got {}", p.facet_angle_deg);
  if (!(p.radius_edge_ratio >= 2))
    fail("tetmesh: radius_edge_ratio must be at least 2, got {}", p.radius_edge_ratio);
  for (const auto& [name, value] :
       {std::pair{"cell_size_mm", p.cell_size_mm}, std::pair{"facet_size_mm", p.facet_size_mm},
        std::pair{"facet_distance_mm", p.facet_distance_mm}})
    if (!std::isfinite(value))
      fail("tetmesh: {} must be finite, got {}", name, value);
  if (p.seed < 0)
    fail("tetmesh: seed must be non-negative, got {}", p.seed);
  if (p.order != 1 && p.order != 2)
    fail("tetmesh: order must be 1 (linear tets) or 2 (10-node tets), got {}", p.order);
}

/// Indices and coordinates first (the topology check reads them), then closed and manifold.
void check_surface(const TriangleSurface& surface)
{
  if (surface.F.rows() == 0)
    fail("tetmesh: the surface is empty ({} vertices, no triangles): nothing to mesh",
         surface.V.rows());
  for (Eigen::Index v = 0; v < surface.V.rows(); ++v)
    if (!surface.V.row(v).allFinite())
      fail("tetmesh: surface vertex {} has a non-finite coordinate", v);
  const auto vertex_count = static_cast<int>(surface.V.rows());
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (surface.F(f, k) < 0 || surface.F(f, k) >= vertex_count)
        fail("tetmesh: surface triangle {} has vertex index {} outside 0..{}", f, surface.F(f, k),
             vertex_count - 1);
  io::require_closed_manifold(surface, "tetmesh: the surface");
}

void check_features(const std::vector<FeatureLine>& features)
{
  for (std::size_t f = 0; f < features.size(); ++f) {
    if (features[f].size() < 2)
      fail("tetmesh: feature line {} has {} point(s); a line needs two", f, features[f].size());
    for (std::size_t p = 0; p < features[f].size(); ++p)
      if (!features[f][p].allFinite())
        fail("tetmesh: point {} of feature line {} has a non-finite coordinate", p, f);
  }
}

void check_orientation(const TetMesh& mesh)
{
  for (Eigen::Index t = 0; t < mesh.T.rows(); ++t) {
    const double volume = signed_tet_volume(mesh.V.row(mesh.T(t, 0)), mesh.V.row(mesh.T(t, 1)),
                                            mesh.V.row(mesh.T(t, 2)), mesh.V.row(mesh.T(t, 3)));
    if (!(volume > 0))
      fail<SolverError>("tetmesh: CGAL produced tet {} with volume {} mm^3 (not positive)", t,
                        volume);
  }
}

/// The sizes left at 0 in `parameters`, from the band's thickness.
Parameters sizes_for_thickness(Parameters resolved, double thickness)
{
  // 10-node tets bend where linear ones lock, so they need not be thinner than the band: on the
  // female HRA MCL (1.4 mm thick) 2.4 and 1.8 mm gave the 0.9 mm mesh's answer (docs/build.md).
  const double size = resolved.order == 2 ? kQuadraticSizeOverThickness * thickness : thickness / 2;
  if (resolved.cell_size_mm <= 0)
    resolved.cell_size_mm = size;
  if (resolved.facet_size_mm <= 0)
    resolved.facet_size_mm = size;
  if (resolved.facet_distance_mm <= 0)
    resolved.facet_distance_mm = thickness / 20;
  return resolved;
}

} // namespace

double characteristic_thickness(const TriangleSurface& surface)
{
  const double area = ligsim::surface_area(surface);
  const double thickness = 2.0 * std::abs(ligsim::signed_volume(surface)) / area;
  if (!(thickness > 0))
    fail("tetmesh: the surface encloses no volume (area {} mm^2)", area);
  return thickness;
}

Parameters default_sizes(const TriangleSurface& surface, const Parameters& parameters)
{
  return sizes_for_thickness(parameters, characteristic_thickness(surface));
}

Result make_tet_mesh(const TriangleSurface& surface, const Parameters& parameters,
                     const std::vector<FeatureLine>& features)
{
  check_parameters(parameters);
  check_surface(surface);
  check_features(features);
  Result result;
  const double thickness = characteristic_thickness(surface);
  result.used = sizes_for_thickness(parameters, thickness);
  // A protecting ball as wide as the band would leave no room for its other side: on the
  // synthetic band, rim edges of the facet size let the mesh lose 35 % of its volume at 6 mm.
  const double feature_edge_mm = std::min(result.used.facet_size_mm, thickness);
  result.mesh = mesh_with_cgal(surface, features, feature_edge_mm, result.used);
  if (result.mesh.T.rows() == 0)
    fail("tetmesh: Mesh_3 produced no tetrahedra (cell size {} mm, facet size {} mm, facet "
         "distance {} mm): the sizes may be far too large for the surface",
         result.used.cell_size_mm, result.used.facet_size_mm, result.used.facet_distance_mm);
  check_orientation(result.mesh);
  result.quality = measure_quality(result.mesh, surface);
  return result;
}

} // namespace ligsim::tetmesh
