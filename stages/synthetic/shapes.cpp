#include "stages/synthetic/shapes.hpp"

#include "stages/geometry/surface_topology.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <vector>

namespace ligsim::synthetic {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Sweeps a closed convex 2-D section (counter-clockwise, in the (normal, binormal) plane)
/// along `axis` with `rings` rings, and closes both ends with fans.
TriangleSurface sweep(const Axis& axis, const Eigen::Vector3d& binormal_hint,
                      const std::vector<Eigen::Vector2d>& section, int rings)
{
  const int n = static_cast<int>(section.size());
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : section)
    centroid += p / n;
  TriangleSurface surface;
  surface.V.resize(rings * n + 2, 3);
  auto place = [&](double u, const Eigen::Vector2d& p) -> Eigen::Vector3d {
    const Eigen::Vector3d t = axis.tangent(u);
    const Eigen::Vector3d b = (binormal_hint - binormal_hint.dot(t) * t).normalized();
    const Eigen::Vector3d nrm = b.cross(t);
    return axis.point(u) + p.x() * nrm + p.y() * b;
  };
  for (int r = 0; r < rings; ++r) {
    const double u = static_cast<double>(r) / (rings - 1);
    for (int k = 0; k < n; ++k)
      surface.V.row(r * n + k) = place(u, section[k]).transpose();
  }
  // The end fans meet at the section's centroid (inside a convex section).
  const int start_centre = rings * n, end_centre = rings * n + 1;
  surface.V.row(start_centre) = place(0.0, centroid).transpose();
  surface.V.row(end_centre) = place(1.0, centroid).transpose();

  std::vector<Eigen::Vector3i> faces;
  for (int r = 0; r + 1 < rings; ++r)
    for (int k = 0; k < n; ++k) {
      const int a = r * n + k, b = r * n + (k + 1) % n;
      const int c = a + n, d = b + n;
      faces.emplace_back(a, b, d);
      faces.emplace_back(a, d, c);
    }
  for (int k = 0; k < n; ++k) {
    faces.emplace_back(start_centre, (k + 1) % n, k);
    faces.emplace_back(end_centre, (rings - 1) * n + k, (rings - 1) * n + (k + 1) % n);
  }
  surface.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    surface.F.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
  if (signed_volume(surface) < 0.0)
    surface.F.col(1).swap(surface.F.col(2));
  return surface;
}

std::vector<Eigen::Vector2d> circle(double radius, int segments)
{
  std::vector<Eigen::Vector2d> points;
  for (int k = 0; k < segments; ++k) {
    const double phi = 2.0 * kPi * k / segments;
    points.emplace_back(radius * std::cos(phi), radius * std::sin(phi));
  }
  return points;
}

/// A rectangle with rounded corners, counter-clockwise, centred at the origin, its straight
/// sides split into pieces no longer than `step`.
std::vector<Eigen::Vector2d> rounded_rectangle(double width, double height, double corner,
                                               int corner_segments, double step)
{
  const Eigen::Vector2d half(width / 2 - corner, height / 2 - corner);
  const Eigen::Vector2d centres[4] = {
      {half.x(), half.y()}, {-half.x(), half.y()}, {-half.x(), -half.y()}, {half.x(), -half.y()}};
  std::vector<Eigen::Vector2d> points;
  for (int c = 0; c < 4; ++c) {
    for (int k = 0; k <= corner_segments; ++k) {
      const double phi = kPi / 2 * (c + static_cast<double>(k) / corner_segments);
      points.push_back(centres[c] + corner * Eigen::Vector2d(std::cos(phi), std::sin(phi)));
    }
    // The straight side to the next corner, without its end points.
    const double phi = kPi / 2 * (c + 1);
    const Eigen::Vector2d from = points.back();
    const Eigen::Vector2d to =
        centres[(c + 1) % 4] + corner * Eigen::Vector2d(std::cos(phi), std::sin(phi));
    const int pieces = std::max(1, static_cast<int>(std::ceil((to - from).norm() / step)));
    for (int k = 1; k < pieces; ++k)
      points.push_back(from + (to - from) * (static_cast<double>(k) / pieces));
  }
  return points;
}

int rings_for(double length, double step)
{
  return std::max(2, static_cast<int>(std::ceil(length / step)) + 1);
}

} // namespace

Shape cylinder(double radius_mm, double length_mm, int segments)
{
  Shape shape;
  shape.axis.length_mm = length_mm;
  shape.axis.point = [length_mm](double u) { return Eigen::Vector3d(0, 0, u * length_mm); };
  shape.axis.tangent = [](double) { return Eigen::Vector3d(0, 0, 1); };
  const double step = 2 * kPi * radius_mm / segments * 2;
  shape.surface = sweep(shape.axis, Eigen::Vector3d::UnitY(), circle(radius_mm, segments),
                        rings_for(length_mm, step));
  return shape;
}

Shape torus_tube(double bend_radius_mm, double tube_radius_mm, double angle_deg, int segments)
{
  Shape shape;
  const double span = angle_deg * kPi / 180.0;
  shape.axis.length_mm = bend_radius_mm * span;
  shape.axis.point = [=](double u) {
    return Eigen::Vector3d(bend_radius_mm * std::cos(u * span), bend_radius_mm * std::sin(u * span),
                           0);
  };
  shape.axis.tangent = [=](double u) {
    return Eigen::Vector3d(-std::sin(u * span), std::cos(u * span), 0);
  };
  const double step = 2 * kPi * tube_radius_mm / segments * 2;
  shape.surface = sweep(shape.axis, Eigen::Vector3d::UnitZ(), circle(tube_radius_mm, segments),
                        rings_for(shape.axis.length_mm, step));
  return shape;
}

Shape ligament_band(double length_mm, double width_mm, double thickness_mm)
{
  Shape shape;
  // A circular arc in the xz-plane with a sagitta of 8 % of the length: bowed like an MCL
  // wrapping the medial condyle.
  const double sagitta = 0.08 * length_mm;
  const double bend = (length_mm * length_mm / 4 + sagitta * sagitta) / (2 * sagitta);
  const double half_angle = std::asin(length_mm / 2 / bend);
  const Eigen::Vector3d centre(-(bend - sagitta), 0, length_mm / 2);
  shape.axis.length_mm = 2 * half_angle * bend;
  shape.axis.point = [=](double u) {
    const double phi = -half_angle + 2 * half_angle * u;
    return Eigen::Vector3d(centre.x() + bend * std::cos(phi), 0, centre.z() + bend * std::sin(phi));
  };
  shape.axis.tangent = [=](double u) {
    const double phi = -half_angle + 2 * half_angle * u;
    return Eigen::Vector3d(-std::sin(phi), 0, std::cos(phi));
  };
  // Section: thickness along x (the bow's normal), width along y.
  const double step = std::min(1.0, thickness_mm / 3);
  auto section = rounded_rectangle(thickness_mm, width_mm, 0.4 * thickness_mm, 6, step);
  shape.surface =
      sweep(shape.axis, Eigen::Vector3d::UnitY(), section, rings_for(shape.axis.length_mm, step));

  // Bone proxies. The femur caps the proximal end, 0.2 mm above it. The tibia is a 10 mm thick
  // slab hugging the inner (concave) side of the distal quarter, 0.3 mm away, as the MCL's long
  // tibial insertion lies on the tibia.
  const Eigen::Vector3d top = shape.axis.point(1.0);
  shape.femur = box(top + Eigen::Vector3d(-15, -20, 0.2), top + Eigen::Vector3d(15, 20, 30));
  Axis distal;
  distal.point = [axis = shape.axis](double u) { return axis.point(0.25 * u); };
  distal.tangent = [axis = shape.axis](double u) { return axis.tangent(0.25 * u); };
  distal.length_mm = 0.25 * shape.axis.length_mm;
  const double gap = 0.3, depth = 10.0;
  std::vector<Eigen::Vector2d> slab;
  for (const Eigen::Vector2d& corner :
       {Eigen::Vector2d(-thickness_mm / 2 - gap, -width_mm),
        Eigen::Vector2d(-thickness_mm / 2 - gap, width_mm),
        Eigen::Vector2d(-thickness_mm / 2 - gap - depth, width_mm),
        Eigen::Vector2d(-thickness_mm / 2 - gap - depth, -width_mm)})
    slab.push_back(corner);
  shape.tibia = sweep(distal, Eigen::Vector3d::UnitY(), slab, rings_for(distal.length_mm, 1.0));
  return shape;
}

TriangleSurface box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi)
{
  TriangleSurface surface;
  surface.V.resize(8, 3);
  for (int i = 0; i < 8; ++i)
    surface.V.row(i) << ((i & 1) ? hi.x() : lo.x()), ((i & 2) ? hi.y() : lo.y()),
        ((i & 4) ? hi.z() : lo.z());
  surface.F.resize(12, 3);
  surface.F << 0, 2, 1, 1, 2, 3, // z = lo
      4, 5, 6, 5, 7, 6,          // z = hi
      0, 1, 4, 1, 5, 4,          // y = lo
      2, 6, 3, 3, 6, 7,          // y = hi
      0, 4, 2, 2, 4, 6,          // x = lo
      1, 3, 5, 3, 7, 5;          // x = hi
  return surface;
}

} // namespace ligsim::synthetic
