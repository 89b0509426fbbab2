#include "stages/tetmesh/surface_distance.hpp"

#include "common/error.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cmath>
#include <vector>

namespace ligsim::tetmesh {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Triangle = Kernel::Triangle_3;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, std::vector<Triangle>::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

Kernel::Point_3 point(const Points& P, Eigen::Index row)
{
  return {P(row, 0), P(row, 1), P(row, 2)};
}

} // namespace

Eigen::VectorXd distances_to_surface(const Points& points, const TriangleSurface& surface)
{
  if (surface.F.rows() == 0)
    fail("cannot measure distances to an empty surface");
  std::vector<Triangle> triangles;
  triangles.reserve(static_cast<std::size_t>(surface.F.rows()));
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f)
    triangles.emplace_back(point(surface.V, surface.F(f, 0)), point(surface.V, surface.F(f, 1)),
                           point(surface.V, surface.F(f, 2)));
  Tree tree(triangles.begin(), triangles.end());
  tree.accelerate_distance_queries();

  Eigen::VectorXd distances(points.rows());
  for (Eigen::Index p = 0; p < points.rows(); ++p)
    distances(p) = std::sqrt(tree.squared_distance(point(points, p)));
  return distances;
}

} // namespace ligsim::tetmesh
