#pragma once
/// @brief A surface's triangles as points with an area and a normal: what the anatomy's
/// landmarks are found from (area-weighted, so that a coarse or uneven mesh weighs its parts
/// by their size, not by their vertex count).

#include "common/mesh.hpp"

#include <Eigen/Core>

#include <functional>
#include <optional>

namespace ligsim::anatomy {

struct Facets {
  Points centroid;      ///< #F x 3, mm
  Points normal;        ///< #F x 3, unit, outward for a closed outward surface
  Eigen::VectorXd area; ///< #F, mm^2
};

Facets facets_of(const TriangleSurface& surface);

/// The area-weighted centroid of the facets `keep` selects (by index), and their area; none
/// when they have no area.
struct Region {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  double area_mm2 = 0.0;
};
std::optional<Region> region(const Facets& facets, const std::function<bool(Eigen::Index)>& keep);

/// The largest value of `height` (mm) over the facets: e.g. the most proximal point's height.
double highest(const Facets& facets, const Eigen::Vector3d& direction);

} // namespace ligsim::anatomy
