#pragma once
/// Shared by the stage tests: a synthetic shape taken through voxelize and distance.

#include "common/progress.hpp"
#include "stages/distance/distance.hpp"
#include "stages/geometry/polyline.hpp"
#include "stages/geometry/surface_query.hpp"
#include "stages/synthetic/shapes.hpp"
#include "stages/voxelize/voxelize.hpp"

#include <Eigen/Geometry>

#include <algorithm>

namespace ligsim::test {

struct VoxelisedShape {
  synthetic::Shape shape;
  SurfaceQuery query;
  Mask mask;
  ScalarGrid distance;
};

inline VoxelisedShape voxelise(synthetic::Shape shape, double spacing)
{
  Progress::set_quiet(true);
  SurfaceQuery query(shape.surface);
  voxelize::Parameters parameters;
  parameters.spacing_mm = spacing;
  const vdb::LevelSet level_set = voxelize::level_set(query.surface(), parameters);
  Mask mask = level_set.inside();
  ScalarGrid distance = distance::signed_distance(level_set, query);
  return {std::move(shape), std::move(query), std::move(mask), std::move(distance)};
}

/// The shape moved rigidly: rotated by `rotation` about the origin, then shifted.
inline synthetic::Shape transformed(synthetic::Shape shape, const Eigen::Matrix3d& rotation,
                                    const Eigen::Vector3d& shift)
{
  for (Eigen::Index v = 0; v < shape.surface.V.rows(); ++v)
    shape.surface.V.row(v) = (rotation * shape.surface.V.row(v).transpose() + shift).transpose();
  auto point = shape.axis.point;
  auto tangent = shape.axis.tangent;
  shape.axis.point = [=](double u) { return Eigen::Vector3d(rotation * point(u) + shift); };
  shape.axis.tangent = [=](double u) { return Eigen::Vector3d(rotation * tangent(u)); };
  return shape;
}

/// Distance from `p` to the shape's true axis (sampled finely), mm.
inline double distance_to_axis(const synthetic::Axis& axis, const Eigen::Vector3d& p,
                               double* u_closest = nullptr)
{
  // A coarse scan, then a fine one around the best coarse sample (resolution 2.5e-5 in u).
  double best = 1e300, best_u = 0.0;
  auto scan = [&](double from, double to, int samples) {
    for (int s = 0; s <= samples; ++s) {
      const double u = std::clamp(from + (to - from) * s / samples, 0.0, 1.0);
      const double d = (axis.point(u) - p).norm();
      if (d < best) {
        best = d;
        best_u = u;
      }
    }
  };
  scan(0.0, 1.0, 200);
  scan(best_u - 0.005, best_u + 0.005, 400);
  if (u_closest)
    *u_closest = best_u;
  return best;
}

/// One point as a 1 x 3 point list (an attachment area of one point).
inline Points as_points(const Eigen::Vector3d& p)
{
  return p.transpose();
}

/// The shape's true axis as a polyline with `count` points.
inline Polyline axis_polyline(const synthetic::Axis& axis, int count = 400)
{
  Points points(count, 3), tangents(count, 3);
  for (int i = 0; i < count; ++i) {
    const double u = static_cast<double>(i) / (count - 1);
    points.row(i) = axis.point(u).transpose();
    tangents.row(i) = axis.tangent(u).transpose();
  }
  return Polyline(points, tangents);
}

/// A structured tet mesh (each cube split into 6 positive tets around its main diagonal) over the
/// mask's inside voxels, `stride` voxels per cube: a stand-in for the CGAL mesh in stage tests.
inline TetMesh structured_tets(const Mask& mask, int stride)
{
  TetMesh mesh;
  const Eigen::Vector3i cubes = (mask.dims.array() - 1) / stride;
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector4i> tets;
  auto node = [&](int i, int j, int k) {
    points.push_back(mask.point(i * stride, j * stride, k * stride));
    return static_cast<int>(points.size()) - 1;
  };
  // Corner c of a cube: bit 0 -> +x, bit 1 -> +y, bit 2 -> +z. Paths 0 -> 7 through the cube.
  static const int paths[6][2] = {{1, 3}, {1, 5}, {2, 3}, {2, 6}, {4, 5}, {4, 6}};
  for (int k = 0; k < cubes.z(); ++k)
    for (int j = 0; j < cubes.y(); ++j)
      for (int i = 0; i < cubes.x(); ++i) {
        const Eigen::Vector3d centre = mask.point(
            (2 * i + 1) * stride / 2, (2 * j + 1) * stride / 2, (2 * k + 1) * stride / 2);
        const Eigen::Vector3i c = mask.voxel_coordinates(centre).array().round().cast<int>();
        if (!mask(c.x(), c.y(), c.z()))
          continue;
        int corner[8];
        for (int b = 0; b < 8; ++b)
          corner[b] = node(i + (b & 1), j + ((b >> 1) & 1), k + ((b >> 2) & 1));
        for (const auto& path : paths) {
          Eigen::Vector4i t(corner[0], corner[path[0]], corner[path[1]], corner[7]);
          const Eigen::Vector3d p0 = points[t[0]], p1 = points[t[1]], p2 = points[t[2]],
                                p3 = points[t[3]];
          if ((p1 - p0).dot((p2 - p0).cross(p3 - p0)) < 0)
            std::swap(t[1], t[2]);
          tets.push_back(t);
        }
      }
  mesh.V.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t p = 0; p < points.size(); ++p)
    mesh.V.row(static_cast<Eigen::Index>(p)) = points[p].transpose();
  mesh.T.resize(static_cast<Eigen::Index>(tets.size()), 4);
  for (std::size_t t = 0; t < tets.size(); ++t)
    mesh.T.row(static_cast<Eigen::Index>(t)) = tets[t].transpose();
  return mesh;
}

} // namespace ligsim::test
