#pragma once
/// @brief Repair of a defective segmented surface: what was wrong, where, and what was done.
///
/// Real segmentations exported from Slicer, ITK-SNAP or scanners carry duplicated and degenerate
/// triangles, flipped triangles, non-manifold edges and vertices, small stray pieces and small
/// holes. `repair_surface` fixes those (CGAL Polygon_mesh_processing) and lists every repair with
/// counts and locations; what it cannot fix (a big hole) is left for the closed-manifold check,
/// which then names where it is.

#include "common/mesh.hpp"

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace ligsim::repair {

/// One place a defect was found: a point (mm) and, where it is an edge or a vertex, the vertex
/// indices of the surface as read (coincident points merged).
struct Location {
  Eigen::Vector3d point_mm = Eigen::Vector3d::Zero();
  std::vector<int> vertices;
  std::vector<Eigen::Vector3d> vertex_points_mm; ///< their coordinates, for edges and vertices
  double area_mm2 = 0.0; ///< a filled hole: the patch's area; a removed piece: its area
  int triangles = 0;     ///< a filled hole: triangles added; a removed piece: its triangles
};

/// One kind of defect and what was done about it.
struct Repair {
  std::string kind;   ///< "degenerate_triangles", "non_manifold_edges", ...
  std::string action; ///< "removed", "split", "flipped", "filled", "merged"
  int count = 0;
  std::vector<Location> locations; ///< the first few
  double area_mm2 = 0.0;           ///< sum of the locations' areas, all of them (holes, pieces)
  int triangles = 0;               ///< sum of the locations' triangles, all of them (holes, pieces)
};

struct Report {
  std::vector<Repair> repairs; ///< only kinds that were found, in the order they were fixed
  int triangles_before = 0;
  int triangles_after = 0;

  bool empty() const { return repairs.empty(); }
  const Repair* find(const std::string& kind) const;
};

struct Parameters {
  /// A connected piece whose area is below this fraction of the largest piece's is stray.
  double stray_area_fraction = 0.05;
  /// A hole is small (filled) when its area, as a fan from its centroid, is below this fraction
  /// of the surface's area.
  double hole_area_fraction = 0.02;
};

struct Result {
  TriangleSurface surface;
  Report report;
  /// For each vertex of `surface`, the input vertex it comes from (-1: a vertex added to fill a
  /// hole), so point data can follow the repair.
  std::vector<int> source_vertex;
};

/// Repairs `surface`; returns it unchanged, with an empty report, when nothing is wrong.
Result repair_surface(const TriangleSurface& surface, const Parameters& parameters = {});

/// Makes a bone surface one closed, consistently and outward oriented shell, as contact needs
/// (a level set signed by flood fill, an inside test by winding number): coincident vertices
/// merged, degenerate and duplicate triangles removed, non-manifold edges and vertices split,
/// triangles turned to agree, every hole filled whatever its size with a fair patch (smooth
/// across the rim; "holes", with each patch's area and triangles), then the shell of the
/// largest enclosed volume kept: the other pieces
/// are "inner_cavities" (inside it) or "stray_components" (outside), removed; last the whole
/// surface turned outward ("inward_orientation", the triangles turned). Throws InputError,
/// with `what` ("femur surface 'femur.stl'") and the place, if the result is still open.
Result repair_bone(const TriangleSurface& surface, const std::string& what);

/// The report for summary.json.
nlohmann::json to_json(const Report& report);

/// One line per kind of repair, for stderr: "removed 2 degenerate triangles (first near ...)".
std::vector<std::string> describe(const Report& report);

} // namespace ligsim::repair
