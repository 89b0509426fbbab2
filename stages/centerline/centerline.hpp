#pragma once
/// @brief Stage 3: the minimal-cost path between the two attachment areas (paper eq. 25).

#include "common/mesh.hpp"
#include "stages/geometry/grid.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace ligsim::centerline {

/// Which stretch of the ligament the centerline spans.
enum class Span {
  /// The paper's: from the voxel nearest the mean of A1 to the one nearest the mean of A2.
  means,
  /// Through the whole attachment areas: from the A1 voxel farthest (in path length inside the
  /// shape) from the A2 end to the A2 voxel farthest from the A1 mean, so the line also runs
  /// along a long insertion (the MCL's tibial one) instead of stopping at its middle.
  attachments,
};

Span parse_span(const std::string& name);
std::string to_string(Span span);

struct Parameters {
  Span span = Span::means;
  /// Weight of the medial term: 0 gives the shortest path, 1 the path farthest from the surface.
  double alpha = 0.1;
  /// Refine the voxel path towards the continuous minimum of eq. 25: straighten it where a
  /// straight segment inside the shape costs no more (removes the 26-neighbourhood's
  /// staircase), then relax its points by gradient descent on eq. 25.
  bool refine = true;
  int relax_iterations = 100;
  /// Continue both ends along their direction to the surface, so that every point of the shape
  /// has a centerline point beside it, not only behind the end (the paper notes unreliable
  /// fibers at the attachments when the line stops short of the boundary).
  bool extend_to_surface = true;
  /// Spacing of the output points; <= 0: the voxel spacing.
  double point_spacing_mm = 0.0;
  /// Laplacian smoothing passes on the resampled line (end points fixed).
  int smoothing_passes = 3;
};

struct Centerline {
  Points points;                           ///< #P x 3, mm, from the start to the end
  Points tangents;                         ///< #P x 3 unit tangents
  std::vector<Eigen::Vector3i> voxel_path; ///< Dijkstra's path, voxel indices
  Eigen::Vector3i start_voxel, end_voxel;
  double path_cost = 0.0; ///< eq. 25 along the voxel path
  double length_mm = 0.0;
};

/// Minimal-cost path over the inside voxels of `mask` (26-neighbourhood, Dijkstra on the sparse
/// grid) between the attachment areas `start_area` (A1) and `end_area` (A2), #points x 3, mm,
/// chosen by `parameters.span`. A step from voxel a to b costs |dP| (alpha (1/dn_a^2 + 1/dn_b^2)/2
/// + (1 - alpha)) with dn = d / d_max: the distance is scaled by the largest inside distance, so
/// the cost does not depend on the unit or the size of the shape, and alpha means the same on a 3
/// mm and a 30 mm thick structure. Throws InputError if the two voxels are not connected inside the
/// mask.
Centerline extract(const Mask& mask, const ScalarGrid& distance, const Points& start_area,
                   const Points& end_area, const Parameters& parameters);

/// Eq. 25 integrated along a polyline, with d interpolated from `distance` (scaled as above).
double path_cost(const Points& points, const ScalarGrid& distance, double alpha);

} // namespace ligsim::centerline
