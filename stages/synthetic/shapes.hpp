#pragma once
/// @brief Reproducible synthetic shapes with known axes, for tests and benchmarks.
///
/// Every shape is a closed, outward-oriented triangle surface swept along a known curve, so
/// tests can compare centerlines, distances and fibers with analytic answers.

#include "common/mesh.hpp"

#include <Eigen/Core>

#include <functional>
#include <optional>

namespace ligsim::synthetic {

/// The true axis of a swept shape: position and unit tangent at arc parameter u in [0, 1].
struct Axis {
  std::function<Eigen::Vector3d(double)> point;
  std::function<Eigen::Vector3d(double)> tangent;
  double length_mm = 0.0;
};

struct Shape {
  TriangleSurface surface;
  Axis axis;
  std::optional<TriangleSurface> femur; ///< bone proxy touching the u = 1 end, if any
  std::optional<TriangleSurface> tibia; ///< bone proxy touching the u = 0 end, if any
};

/// A straight circular cylinder of `radius` along +z from the origin, `length` long.
Shape cylinder(double radius_mm = 3.0, double length_mm = 30.0, int segments = 96);

/// A tube of circular section (`tube_radius`) along a circular arc of radius `bend_radius`
/// in the xy-plane, centred at the origin, spanning `angle_deg` from the +x axis.
Shape torus_tube(double bend_radius_mm = 20.0, double tube_radius_mm = 3.0,
                 double angle_deg = 120.0, int segments = 64);

/// An MCL-like flat band: a rounded `width` x `thickness` section swept along a gently bowed
/// arc `length` long running along +z, with box proxies of the femur (above) and the tibia
/// (beside the distal third, as the MCL's long tibial insertion).
Shape ligament_band(double length_mm = 80.0, double width_mm = 12.0, double thickness_mm = 3.0);

/// A closed axis-aligned box.
TriangleSurface box(const Eigen::Vector3d& min_corner, const Eigen::Vector3d& max_corner);

} // namespace ligsim::synthetic
