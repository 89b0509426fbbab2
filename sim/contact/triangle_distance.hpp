#pragma once
/// @brief The unsigned distance from a point to a surface's triangles (VTK's
/// vtkImplicitPolyDataDistance, an exact nearest-triangle search over a cell locator).

#include "common/mesh.hpp"

#include <Eigen/Core>

#include <memory>

namespace ligsim::sim {

class TriangleDistance {
public:
  /// `surface`: triangles, mm (copied).
  explicit TriangleDistance(const TriangleSurface& surface);
  ~TriangleDistance();
  TriangleDistance(const TriangleDistance&) = delete;
  TriangleDistance& operator=(const TriangleDistance&) = delete;

  /// The distance from `p` to the nearest triangle, mm.
  double operator()(const Eigen::Vector3d& p) const;

private:
  struct Locator;
  std::unique_ptr<Locator> m_locator;
};

} // namespace ligsim::sim
