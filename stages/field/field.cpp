#include "stages/field/field.hpp"

#include "common/error.hpp"
#include "common/progress.hpp"
#include "stages/geometry/polyline.hpp"
#include "stages/geometry/surface_query.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>

#include <cmath>

namespace ligsim::field {

Method parse_method(const std::string& name)
{
  if (name == "geometric")
    return Method::geometric;
  if (name == "laplace")
    return Method::laplace;
  fail("unknown field method '{}' (use 'geometric' or 'laplace')", name);
}

std::string to_string(Method method)
{
  return method == Method::geometric ? "geometric" : "laplace";
}

namespace {

Field geometric_field(const Mask& mask, const Polyline& centerline, const SurfaceQuery& surface)
{
  // Written only on the mask's bricks (allocated up front, so threads never allocate).
  Field field{ScalarGrid::with_bricks_of(mask, 1.0f)};
  const auto bricks = static_cast<std::ptrdiff_t>(mask.brick_count());
  Progress progress("field (geometric)", static_cast<std::size_t>(bricks));
  int missed = 0, clamped = 0;
#pragma omp parallel for schedule(dynamic, 4) reduction(+ : missed, clamped)
  for (std::ptrdiff_t b = 0; b < bricks; ++b) {
    mask.for_each_in_brick(static_cast<std::size_t>(b),
                           [&](const Eigen::Vector3i& v, std::uint8_t inside) {
                             if (!inside)
                               return;
                             float* value = field.values.find(v.x(), v.y(), v.z());
                             const Eigen::Vector3d x = mask.point_of(v);
                             const Polyline::Projection c = centerline.project(x);
                             if (c.distance < 1e-9 * mask.spacing) {
                               *value = 0.0f;
                               return;
                             }
                             const Eigen::Vector3d direction = (x - c.point) / c.distance;
                             const auto boundary = surface.first_hit(c.point, direction);
                             if (!boundary) {
                               ++missed;
                               return; // stays 1
                             }
                             const double d = c.distance / (*boundary - c.point).norm();
                             if (d > 1.0)
                               ++clamped;
                             *value = static_cast<float>(std::min(d, 1.0));
                           });
#pragma omp critical(field_progress)
    progress.advance();
  }
  progress.finish();
  field.rays_missed = missed;
  field.clamped = clamped;
  return field;
}

/// Marks the voxels the centerline passes through (sampled at a quarter voxel).
Mask centerline_voxels(const Mask& mask, const Polyline& centerline)
{
  Mask on_line = Mask::like(mask, 0);
  const Points& p = centerline.points();
  for (Eigen::Index s = 0; s + 1 < p.rows(); ++s) {
    const Eigen::Vector3d a = p.row(s), b = p.row(s + 1);
    const int samples =
        std::max(1, static_cast<int>(std::ceil(4.0 * (b - a).norm() / mask.spacing)));
    for (int t = 0; t <= samples; ++t) {
      const Eigen::Vector3d v = mask.voxel_coordinates(a + (b - a) * (double(t) / samples));
      const Eigen::Vector3i ijk = v.array().round().cast<int>();
      if (mask.contains(ijk))
        on_line.set(ijk.x(), ijk.y(), ijk.z(), 1);
    }
  }
  return on_line;
}

Field laplace_field(const Mask& mask, const Polyline& centerline, const Parameters& parameters)
{
  const Mask zero = centerline_voxels(mask, centerline);
  // Unknowns: inside voxels off the centerline, numbered on the mask's bricks. Neighbours on
  // the line contribute 0. Outside neighbours contribute the boundary value 1, except across
  // the faces the centerline runs into (the attachment ends: the neighbour's direction within
  // 45 degrees of the line's tangent), where the flux vanishes instead: fibers run into those
  // faces, not along them.
  auto unknown = Grid<std::int32_t>::with_bricks_of(mask, -1);
  std::vector<Eigen::Vector3i> voxel_of;
  mask.for_each_stored([&](const Eigen::Vector3i& v, std::uint8_t inside) {
    if (inside && !zero(v)) {
      *unknown.find(v.x(), v.y(), v.z()) = static_cast<std::int32_t>(voxel_of.size());
      voxel_of.push_back(v);
    }
  });
  const auto n = static_cast<Eigen::Index>(voxel_of.size());
  // Filled column by column (the matrix is symmetric: column `row` holds row `row`), straight
  // into compressed storage, without a triplet list.
  Eigen::SparseMatrix<double> laplacian(n, n);
  laplacian.reserve(Eigen::VectorXi::Constant(n, 7));
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  static const int offsets[6][3] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                    {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
  constexpr double kEndFaceCosine = 0.70710678;
  for (Eigen::Index row = 0; row < n; ++row) {
    const Eigen::Vector3i a = voxel_of[static_cast<std::size_t>(row)];
    double diagonal = 6.0;
    Eigen::Vector3d tangent = Eigen::Vector3d::Zero();
    bool tangent_known = false;
    for (const auto& o : offsets) {
      const int i = a.x() + o[0], j = a.y() + o[1], k = a.z() + o[2];
      const bool inside = mask.contains(i, j, k) && mask(i, j, k);
      if (!inside) {
        if (!tangent_known) {
          tangent = centerline.project(mask.point_of(a)).tangent;
          tangent_known = true;
        }
        if (std::abs(tangent.dot(Eigen::Vector3d(o[0], o[1], o[2]))) > kEndFaceCosine)
          diagonal -= 1.0; // zero flux across an end face
        else
          rhs[row] += 1.0;
        continue;
      }
      const int column = unknown(i, j, k);
      if (column >= 0)
        laplacian.insert(column, row) = -1.0;
    }
    laplacian.insert(row, row) = diagonal;
  }
  laplacian.makeCompressed();

  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> cg;
  cg.setTolerance(parameters.laplace_tolerance);
  cg.setMaxIterations(parameters.laplace_max_iterations);
  cg.compute(laplacian);
  const Eigen::VectorXd solution = cg.solve(rhs);
  if (cg.info() != Eigen::Success)
    fail<SolverError>("the Laplace field did not converge: relative residual {:.2e} after {} "
                      "CG iterations (limit {})",
                      cg.error(), cg.iterations(), parameters.laplace_max_iterations);

  Field field{ScalarGrid::with_bricks_of(mask, 1.0f)};
  mask.for_each_stored([&](const Eigen::Vector3i& v, std::uint8_t inside) {
    if (inside && zero(v))
      *field.values.find(v.x(), v.y(), v.z()) = 0.0f;
  });
  for (Eigen::Index row = 0; row < n; ++row) {
    const Eigen::Vector3i& v = voxel_of[static_cast<std::size_t>(row)];
    *field.values.find(v.x(), v.y(), v.z()) = static_cast<float>(solution[row]);
  }
  field.iterations = static_cast<int>(cg.iterations());
  field.residual = cg.error();
  return field;
}

} // namespace

Field diffusion_field(const Mask& mask, const Polyline& centerline, const SurfaceQuery& surface,
                      const Parameters& parameters)
{
  return parameters.method == Method::geometric ? geometric_field(mask, centerline, surface)
                                                : laplace_field(mask, centerline, parameters);
}

} // namespace ligsim::field
