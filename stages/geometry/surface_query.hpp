#pragma once
/// @brief Geometric queries on a closed triangle surface: distance, closest point, ray hits.
///
/// Backed by a CGAL AABB tree, kept inside surface_query.cpp so that no other translation
/// unit pays CGAL's compile time.

#include "common/mesh.hpp"

#include <Eigen/Core>

#include <memory>
#include <optional>
#include <vector>

namespace ligsim {

class SurfaceQuery {
public:
  /// Builds the tree over `surface` (kept by value). The surface must be non-empty.
  explicit SurfaceQuery(const TriangleSurface& surface);
  ~SurfaceQuery();
  SurfaceQuery(SurfaceQuery&&) noexcept;
  SurfaceQuery& operator=(SurfaceQuery&&) noexcept;

  struct Closest {
    Eigen::Vector3d point; ///< closest point on the surface, mm
    double distance;       ///< mm
    int face;              ///< index of the triangle it lies on
  };
  Closest closest(const Eigen::Vector3d& p) const;
  double distance(const Eigen::Vector3d& p) const { return closest(p).distance; }

  /// Parameters t > 0 (sorted) where origin + t * direction crosses the surface.
  std::vector<double> ray_hits(const Eigen::Vector3d& origin,
                               const Eigen::Vector3d& direction) const;

  /// The nearest crossing of the ray origin + t * direction, t > min_t, if any.
  std::optional<Eigen::Vector3d> first_hit(const Eigen::Vector3d& origin,
                                           const Eigen::Vector3d& direction,
                                           double min_t = 0.0) const;

  /// Parity test with a ray in a generic direction (robust for closed surfaces).
  bool inside(const Eigen::Vector3d& p) const;

  const TriangleSurface& surface() const;

private:
  struct Tree;
  std::unique_ptr<Tree> m_tree;
};

/// Pairs of triangles that intersect other than along a shared edge or vertex; at most
/// `limit` pairs are returned (the check stops there).
std::vector<std::pair<int, int>> self_intersections(const TriangleSurface& surface,
                                                    std::size_t limit = 16);

} // namespace ligsim
