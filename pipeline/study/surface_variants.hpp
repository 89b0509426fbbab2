#pragma once
/// @brief What a second rater or another MRI could give from one segmentation: the ligament
/// surface moved along its normals, smoothed or roughened, attachment areas grown or shrunk
/// along the surface. Topology is never changed, so vertex i of a variant is vertex i of the
/// source.

#include "common/mesh.hpp"

#include <vector>

namespace ligsim::study {

/// Unit outward vertex normals (area-weighted face normals; the surface is oriented outward).
Points vertex_normals(const TriangleSurface& surface);

/// Every vertex moved by `distance_mm` along its normal (positive: outward).
TriangleSurface offset_surface(const TriangleSurface& surface, double distance_mm);

/// Taubin's lambda/mu smoothing (0.5 / -0.53, umbrella weights): rounds off the staircase and
/// the small bumps of a segmentation without shrinking the shape as plain Laplacian smoothing
/// does. `iterations` lambda/mu pairs.
TriangleSurface smooth_surface(const TriangleSurface& surface, int iterations);

/// Every vertex moved along its normal by a smooth random field (seeded, so reproducible): white
/// noise averaged over its neighbours `passes` times (a bump spans a few edges), scaled to the
/// root-mean-square `rms_mm`.
TriangleSurface roughen_surface(const TriangleSurface& surface, double rms_mm, int passes,
                                unsigned seed);

/// Grows (`distance_mm` > 0) or shrinks (< 0) a vertex set along the surface: grown, the vertices
/// within that geodesic distance (shortest path along the edges) of the set; shrunk, the set's
/// vertices farther than |distance_mm| from every vertex outside it. Sorted indices.
std::vector<int> grow_area(const TriangleSurface& surface, const std::vector<int>& area,
                           double distance_mm);

} // namespace ligsim::study
