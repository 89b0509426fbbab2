#include "stages/anatomy/facets.hpp"

#include <Eigen/Geometry>

#include <limits>

namespace ligsim::anatomy {

Facets facets_of(const TriangleSurface& surface)
{
  const Eigen::Index n = surface.F.rows();
  Facets f{Points(n, 3), Points(n, 3), Eigen::VectorXd(n)};
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector3d a = surface.V.row(surface.F(i, 0)), b = surface.V.row(surface.F(i, 1)),
                          c = surface.V.row(surface.F(i, 2));
    const Eigen::Vector3d twice_area_normal = (b - a).cross(c - a);
    const double twice_area = twice_area_normal.norm();
    f.centroid.row(i) = ((a + b + c) / 3.0).transpose();
    f.area(i) = 0.5 * twice_area;
    f.normal.row(i) = twice_area > 0.0 ? Eigen::RowVector3d(twice_area_normal / twice_area)
                                       : Eigen::RowVector3d::Zero();
  }
  return f;
}

std::optional<Region> region(const Facets& facets, const std::function<bool(Eigen::Index)>& keep)
{
  Region r;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (Eigen::Index i = 0; i < facets.area.size(); ++i)
    if (keep(i)) {
      sum += facets.area(i) * facets.centroid.row(i).transpose();
      r.area_mm2 += facets.area(i);
    }
  if (!(r.area_mm2 > 0.0))
    return std::nullopt;
  r.centroid = sum / r.area_mm2;
  return r;
}

double highest(const Facets& facets, const Eigen::Vector3d& direction)
{
  double top = -std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < facets.area.size(); ++i)
    top = std::max(top, facets.centroid.row(i).dot(direction.transpose()));
  return top;
}

} // namespace ligsim::anatomy
