#pragma once
/// @brief Stage 5: tetrahedral mesh of a closed ligament surface with CGAL Mesh_3, and its quality.
///
/// Default sizes (any size parameter <= 0) come from the surface's characteristic thickness
/// h = 2 V / A (enclosed volume V, area A): for a thin band h is its thickness, for a long
/// round cylinder h is its radius. Then cell_size = facet_size = h / 2 for linear tets and
/// kQuadraticSizeOverThickness h for 10-node ones, and facet_distance = h / 20 (see
/// default_sizes()).
///
/// Steps: Mesh_3 Delaunay refinement; then, if asked, rounds of perturbation each followed by
/// a refinement (perturbation moves surface vertices and can break the facet criteria) until a
/// refinement adds no vertex; then, if asked, sliver exudation (weights only: vertices and
/// surface facets stay). So the refinement criteria hold on the output surface facets, and
/// perturbation and exudation raise the min dihedral angle.

#include "common/mesh.hpp"

namespace ligsim::tetmesh {

/// The default cell and facet size of 10-node tets over the surface's thickness h.
inline constexpr double kQuadraticSizeOverThickness = 1.7;

struct Parameters {
  double cell_size_mm = 0; ///< max tet circumradius; <= 0: h / 2, or 1.7 h for 10-node tets
  /// max radius of a boundary facet's surface Delaunay ball; <= 0: as the cell size
  double facet_size_mm = 0;
  double facet_distance_mm = 0; ///< max distance facet circumcentre to input surface; <= 0: h / 20
  double facet_angle_deg = 25;  ///< min angle of a boundary facet
  double radius_edge_ratio = 2; ///< max tet circumradius / shortest edge during refinement
  bool exude_slivers = true;    ///< CGAL::exude_mesh_3 (sliver exudation by vertex weights)
  bool perturb = true;          ///< CGAL::perturb_mesh_3 (raises the min dihedral angle)
  int seed = 0;                 ///< seed of CGAL's random generator: same seed, same mesh
  /// 1: linear tets; 2: 10-node tets, their boundary mid-edge nodes on the surface (the build's
  /// tetmesh stage adds them, sim/mesh/curved_boundary.hpp; make_tet_mesh meshes the corners).
  int order = 1;
  /// The build's tetmesh stage keeps each footprint's rim as a chain of edges (the `features` of
  /// make_tet_mesh, from stages/attachments/footprint_rim.hpp), so that every mesh binds the same
  /// area. Off by default: on coarse meshes of the synthetic band (sizes above its thickness) the
  /// rims keep the elements beside them small, the companion's search cannot coarsen the mesh
  /// without it losing volume, and Mesh_3 made one flat tet.
  bool footprint_rims = false;
};

struct Quality {
  int tets = 0;
  int nodes = 0;
  double min_dihedral_deg = 0; ///< over all six dihedral angles of every tet
  double max_dihedral_deg = 0;
  double worst_radius_edge_ratio = 0; ///< max circumradius / shortest edge (regular tet: 0.612)
  double min_volume_mm3 = 0;          ///< signed: negative means an inverted tet
  double total_volume_mm3 = 0;
  double surface_volume_mm3 = 0; ///< volume enclosed by the input surface, for comparison
  /// From the tet mesh's boundary vertices to the input surface (Mesh_3 puts them on it).
  double max_surface_distance_mm = 0;
  /// From the boundary facets' centroids to the input surface: how far the facets themselves
  /// depart from it (not bounded by facet_distance_mm; 1.4x it on the MCL).
  double max_facet_centroid_distance_mm = 0;
  /// From the boundary facets' circumcentres to the input surface: at most facet_distance_mm,
  /// since Mesh_3 bounds the distance from each circumcentre to a point of the surface.
  double max_facet_circumcentre_distance_mm = 0;
};

struct Result {
  TetMesh mesh;
  Quality quality;
  Parameters used; ///< with the defaults resolved
};

/// Meshes the volume enclosed by `surface` (closed, manifold, consistently oriented, free of
/// self-intersections; several disjoint closed components are allowed). Every output tet is
/// positively oriented and every output vertex belongs to a tet; the same input, parameters and
/// seed give the same mesh. Throws InputError on an empty, open, non-manifold or
/// self-intersecting surface, bad indices, non-finite coordinates, invalid parameters, or when
/// no tet is produced. Sizes far below the surface's size can take very long (no guard).
/// `features`: curves on the surface (within facet_distance_mm of it) that the mesh keeps as
/// chains of its edges, each at most the facet size and the thickness h long (Mesh_3's
/// protecting balls), so that
/// every mesh of the surface divides it along them alike: the footprints' rims. Throws
/// InputError on a feature with fewer than two points or a non-finite one.
Result make_tet_mesh(const TriangleSurface& surface, const Parameters& parameters,
                     const std::vector<FeatureLine>& features = {});

/// The surface's characteristic thickness h = 2 V / A, mm. Throws InputError when it encloses no
/// volume.
double characteristic_thickness(const TriangleSurface& surface);

/// Quality figures of `mesh`; distances are measured to `surface`.
Quality measure_quality(const TetMesh& mesh, const TriangleSurface& surface);

/// `parameters` with every size <= 0 replaced by the rule in this header's comment.
Parameters default_sizes(const TriangleSurface& surface, const Parameters& parameters);

} // namespace ligsim::tetmesh
