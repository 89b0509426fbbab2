#include "stages/fibers/fibers.hpp"

#include "common/error.hpp"
#include "common/progress.hpp"
#include "stages/geometry/interpolate.hpp"
#include "stages/geometry/polyline.hpp"

#include <cmath>

namespace ligsim::fibers {

namespace {

constexpr double kDegreesPerRadian = 57.29577951308232;

} // namespace

FiberField::FiberField(const Polyline& centerline, ScalarGrid field, Mask mask)
    : m_centerline(centerline)
    , m_field(std::move(field))
    , m_mask(std::move(mask))
{
}

/// Central differences where both neighbours are inside, one-sided where one is, zero outside.
/// Differences never reach across the surface, so the boundary value does not bend the
/// gradient where the shape ends (the attachment faces).
Eigen::Vector3d FiberField::gradient_at_voxel(const Eigen::Vector3i& v) const
{
  auto inside = [&](const Eigen::Vector3i& u) { return m_mask.contains(u) && m_mask(u); };
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  if (!inside(v))
    return g;
  for (int a = 0; a < 3; ++a) {
    Eigen::Vector3i lo = v, hi = v;
    lo[a] -= 1;
    hi[a] += 1;
    if (!inside(lo))
      lo[a] += 1;
    if (!inside(hi))
      hi[a] -= 1;
    const int span = hi[a] - lo[a];
    if (span > 0)
      g[a] = static_cast<double>((m_field(hi) - m_field(lo)) /
                                 static_cast<float>(span * m_field.spacing));
  }
  return g;
}

Eigen::Vector3d FiberField::tangent_at(const Eigen::Vector3d& x) const
{
  return m_centerline.project(x).tangent;
}

FiberField::Sample FiberField::at(const Eigen::Vector3d& x) const
{
  const Eigen::Vector3d tangent = tangent_at(x);
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
  visit_trilinear_voxels(
      m_mask, x, [&](const Eigen::Vector3i& v, double w) { gradient += w * gradient_at_voxel(v); });
  const double g2 = gradient.squaredNorm();
  if (g2 > 0.0) {
    const Eigen::Vector3d projected = tangent - (tangent.dot(gradient) / g2) * gradient;
    // Below ~5.7 degrees between tangent and grad D the isosurface direction is ill-defined.
    if (projected.norm() > 0.1)
      return {projected.normalized(), gradient, true};
  }
  return {tangent, gradient, false};
}

Result per_tet_directions(const TetMesh& mesh, const FiberField& fibers,
                          const Parameters& parameters)
{
  // Barycentric sample points: the centroid and the 4-point Gauss rule's points.
  constexpr double a = 0.5854101966249685, b = 0.1381966011250105;
  std::vector<Eigen::Vector4d> samples;
  if (parameters.samples_per_tet == 1 || parameters.samples_per_tet == 5)
    samples.emplace_back(0.25, 0.25, 0.25, 0.25);
  if (parameters.samples_per_tet == 4 || parameters.samples_per_tet == 5)
    for (int k = 0; k < 4; ++k) {
      Eigen::Vector4d w = Eigen::Vector4d::Constant(b);
      w[k] = a;
      samples.push_back(w);
    }
  if (samples.empty())
    fail("fibers: samples_per_tet must be 1, 4 or 5, got {}", parameters.samples_per_tet);

  Result result;
  result.directions.resize(mesh.T.rows(), 3);
  Progress progress("fibers", static_cast<std::size_t>(mesh.T.rows()));
  double alignment_sum = 0.0;
  int unprojected = 0;
#pragma omp parallel for schedule(dynamic, 64) reduction(+ : alignment_sum, unprojected)
  for (Eigen::Index t = 0; t < mesh.T.rows(); ++t) {
    Eigen::Matrix<double, 4, 3> corners;
    for (int k = 0; k < 4; ++k)
      corners.row(k) = mesh.V.row(mesh.T(t, k));
    const Eigen::Vector3d centroid = corners.colwise().mean().transpose();
    const Eigen::Vector3d reference = fibers.at(centroid).direction;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const Eigen::Vector4d& w : samples) {
      const FiberField::Sample s = fibers.at((corners.transpose() * w).eval());
      unprojected += s.projected ? 0 : 1;
      sum += s.direction.dot(reference) >= 0.0 ? s.direction : Eigen::Vector3d(-s.direction);
    }
    const Eigen::Vector3d direction =
        sum.norm() > 0.0 ? Eigen::Vector3d(sum.normalized()) : reference;
    result.directions.row(t) = direction.transpose();
    const double cosine = std::min(1.0, std::abs(direction.dot(fibers.tangent_at(centroid))));
    alignment_sum += std::acos(cosine) * kDegreesPerRadian;
  }
  progress.finish();
  result.unprojected_samples = unprojected;
  result.mean_alignment_deg = mesh.T.rows() > 0 ? alignment_sum / mesh.T.rows() : 0.0;
  return result;
}

} // namespace ligsim::fibers
