#include "stages/geometry/surface_query.hpp"

#include "common/error.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <iterator>

namespace ligsim {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Vector = Kernel::Vector_3;
using Triangle = Kernel::Triangle_3;
using Ray = Kernel::Ray_3;
using TriangleIterator = std::vector<Triangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, TriangleIterator>;
using AabbTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

Point to_cgal(const Eigen::Vector3d& p)
{
  return {p.x(), p.y(), p.z()};
}
Eigen::Vector3d to_eigen(const Point& p)
{
  return {p.x(), p.y(), p.z()};
}

/// A fixed direction unlikely to be parallel to any mesh edge or face, with three different
/// components: with two equal ones, the ray from any point with y = z stayed in that plane and
/// met a box's edges there, which counted twice and turned inside to outside.
const Eigen::Vector3d kGenericDirection = Eigen::Vector3d(0.5413, 0.5774, 0.6111).normalized();

} // namespace

struct SurfaceQuery::Tree {
  TriangleSurface surface;
  std::vector<Triangle> triangles;
  AabbTree tree;
};

SurfaceQuery::SurfaceQuery(const TriangleSurface& surface)
    : m_tree(std::make_unique<Tree>())
{
  if (surface.F.rows() == 0)
    fail("cannot query an empty surface");
  m_tree->surface = surface;
  auto& triangles = m_tree->triangles;
  triangles.reserve(static_cast<std::size_t>(surface.F.rows()));
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f)
    triangles.emplace_back(to_cgal(surface.V.row(surface.F(f, 0)).transpose()),
                           to_cgal(surface.V.row(surface.F(f, 1)).transpose()),
                           to_cgal(surface.V.row(surface.F(f, 2)).transpose()));
  m_tree->tree.insert(triangles.cbegin(), triangles.cend());
  m_tree->tree.build();
  m_tree->tree.accelerate_distance_queries();
  // One query now builds the distance search structure, so later queries from several
  // threads only read the tree.
  m_tree->tree.closest_point(triangles.front().vertex(0));
}

SurfaceQuery::~SurfaceQuery() = default;
SurfaceQuery::SurfaceQuery(SurfaceQuery&&) noexcept = default;
SurfaceQuery& SurfaceQuery::operator=(SurfaceQuery&&) noexcept = default;

const TriangleSurface& SurfaceQuery::surface() const
{
  return m_tree->surface;
}

SurfaceQuery::Closest SurfaceQuery::closest(const Eigen::Vector3d& p) const
{
  const auto [point, primitive] = m_tree->tree.closest_point_and_primitive(to_cgal(p));
  const Eigen::Vector3d q = to_eigen(point);
  const int face = static_cast<int>(std::distance(m_tree->triangles.cbegin(), primitive));
  return {q, (q - p).norm(), face};
}

std::vector<double> SurfaceQuery::ray_hits(const Eigen::Vector3d& origin,
                                           const Eigen::Vector3d& direction) const
{
  const Ray ray(to_cgal(origin), Vector(direction.x(), direction.y(), direction.z()));
  using Intersection = AabbTree::Intersection_and_primitive_id<Ray>::Type;
  std::vector<Intersection> hits;
  m_tree->tree.all_intersections(ray, std::back_inserter(hits));
  std::vector<double> result;
  result.reserve(hits.size());
  const double length2 = direction.squaredNorm();
  for (const auto& hit : hits) {
    if (const Point* p = boost::get<Point>(&hit.first))
      result.push_back((to_eigen(*p) - origin).dot(direction) / length2);
    // A segment hit means the ray runs inside a triangle's plane: callers use generic
    // directions, so it is skipped rather than counted.
  }
  std::sort(result.begin(), result.end());
  return result;
}

std::optional<Eigen::Vector3d> SurfaceQuery::first_hit(const Eigen::Vector3d& origin,
                                                       const Eigen::Vector3d& direction,
                                                       double min_t) const
{
  if (min_t <= 0.0) {
    // The tree's own nearest-first traversal: much cheaper than collecting every crossing.
    const Ray ray(to_cgal(origin), Vector(direction.x(), direction.y(), direction.z()));
    const auto hit = m_tree->tree.first_intersection(ray);
    if (!hit)
      return std::nullopt;
    if (const Point* p = boost::get<Point>(&hit->first))
      return to_eigen(*p);
    // The ray runs in a triangle's plane: fall back to the crossings of the full list.
  }
  for (double t : ray_hits(origin, direction))
    if (t > min_t)
      return origin + t * direction;
  return std::nullopt;
}

bool SurfaceQuery::inside(const Eigen::Vector3d& p) const
{
  return ray_hits(p, kGenericDirection).size() % 2 == 1;
}

std::vector<std::pair<int, int>> self_intersections(const TriangleSurface& surface,
                                                    std::size_t limit)
{
  using Mesh = CGAL::Surface_mesh<Point>;
  Mesh mesh;
  std::vector<Mesh::Vertex_index> vertices;
  vertices.reserve(static_cast<std::size_t>(surface.V.rows()));
  for (Eigen::Index v = 0; v < surface.V.rows(); ++v)
    vertices.push_back(mesh.add_vertex(to_cgal(surface.V.row(v).transpose())));
  std::vector<int> face_of_index;
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f) {
    const auto face = mesh.add_face(vertices[surface.F(f, 0)], vertices[surface.F(f, 1)],
                                    vertices[surface.F(f, 2)]);
    if (face == Mesh::null_face())
      fail("triangle {} cannot be added to a halfedge mesh (non-manifold)", f);
    face_of_index.push_back(static_cast<int>(f));
  }
  std::vector<std::pair<Mesh::Face_index, Mesh::Face_index>> pairs;
  struct Full {};
  try {
    auto out = boost::make_function_output_iterator([&](const auto& pair) {
      pairs.push_back(pair);
      if (pairs.size() >= limit)
        throw Full{};
    });
    CGAL::Polygon_mesh_processing::self_intersections(mesh, out);
  } catch (const Full&) {
  }
  std::vector<std::pair<int, int>> result;
  for (const auto& [a, b] : pairs)
    result.emplace_back(face_of_index[static_cast<std::size_t>(a)],
                        face_of_index[static_cast<std::size_t>(b)]);
  return result;
}

} // namespace ligsim
