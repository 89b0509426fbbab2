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
  Field field{ScalarGrid::like(mask, 1.0f)};
  Progress progress("field (geometric)", static_cast<std::size_t>(mask.dims.z()));
  int missed = 0, clamped = 0;
  for (int k = 0; k < mask.dims.z(); ++k) {
#pragma omp parallel for schedule(dynamic, 4) reduction(+ : missed, clamped)
    for (int j = 0; j < mask.dims.y(); ++j)
      for (int i = 0; i < mask.dims.x(); ++i) {
        if (!mask(i, j, k))
          continue;
        const Eigen::Vector3d x = mask.point(i, j, k);
        const Polyline::Projection c = centerline.project(x);
        if (c.distance < 1e-9 * mask.spacing) {
          field.values(i, j, k) = 0.0f;
          continue;
        }
        const Eigen::Vector3d direction = (x - c.point) / c.distance;
        const auto boundary = surface.first_hit(c.point, direction);
        if (!boundary) {
          ++missed;
          continue; // stays 1
        }
        const double d = c.distance / (*boundary - c.point).norm();
        if (d > 1.0)
          ++clamped;
        field.values(i, j, k) = static_cast<float>(std::min(d, 1.0));
      }
    progress.advance();
  }
  progress.finish();
  field.rays_missed = missed;
  field.clamped = clamped;
  return field;
}

/// Marks the voxels the centerline passes through (sampled at a quarter voxel).
std::vector<bool> centerline_voxels(const Mask& mask, const Polyline& centerline)
{
  std::vector<bool> on_line(mask.values.size(), false);
  const Points& p = centerline.points();
  for (Eigen::Index s = 0; s + 1 < p.rows(); ++s) {
    const Eigen::Vector3d a = p.row(s), b = p.row(s + 1);
    const int samples =
        std::max(1, static_cast<int>(std::ceil(4.0 * (b - a).norm() / mask.spacing)));
    for (int t = 0; t <= samples; ++t) {
      const Eigen::Vector3d v = mask.voxel_coordinates(a + (b - a) * (double(t) / samples));
      const Eigen::Vector3i ijk = v.array().round().cast<int>();
      if (mask.contains(ijk.x(), ijk.y(), ijk.z()))
        on_line[mask.index(ijk.x(), ijk.y(), ijk.z())] = true;
    }
  }
  return on_line;
}

Field laplace_field(const Mask& mask, const Polyline& centerline, const Parameters& parameters)
{
  const std::vector<bool> zero = centerline_voxels(mask, centerline);
  // Unknowns: inside voxels off the centerline. Neighbours on the line contribute 0. Outside
  // neighbours contribute the boundary value 1, except across the faces the centerline runs
  // into (the attachment ends: the neighbour's direction within 45 degrees of the line's
  // tangent), where the flux vanishes instead: fibers run into those faces, not along them.
  std::vector<int> unknown(mask.values.size(), -1);
  std::vector<std::size_t> voxel_of;
  for (std::size_t v = 0; v < mask.values.size(); ++v)
    if (mask.values[v] && !zero[v]) {
      unknown[v] = static_cast<int>(voxel_of.size());
      voxel_of.push_back(v);
    }
  const auto n = static_cast<Eigen::Index>(voxel_of.size());
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(voxel_of.size() * 7);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  static const int offsets[6][3] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                    {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
  constexpr double kEndFaceCosine = 0.70710678;
  for (Eigen::Index row = 0; row < n; ++row) {
    const Eigen::Vector3i a = mask.ijk(voxel_of[row]);
    double diagonal = 6.0;
    Eigen::Vector3d tangent = Eigen::Vector3d::Zero();
    bool tangent_known = false;
    for (const auto& o : offsets) {
      const int i = a.x() + o[0], j = a.y() + o[1], k = a.z() + o[2];
      const bool inside = mask.contains(i, j, k) && mask(i, j, k);
      if (!inside) {
        if (!tangent_known) {
          tangent = centerline.project(mask.point(voxel_of[row])).tangent;
          tangent_known = true;
        }
        if (std::abs(tangent.dot(Eigen::Vector3d(o[0], o[1], o[2]))) > kEndFaceCosine)
          diagonal -= 1.0; // zero flux across an end face
        else
          rhs[row] += 1.0;
        continue;
      }
      const int column = unknown[mask.index(i, j, k)];
      if (column >= 0)
        entries.emplace_back(row, column, -1.0);
    }
    entries.emplace_back(row, row, diagonal);
  }
  Eigen::SparseMatrix<double> laplacian(n, n);
  laplacian.setFromTriplets(entries.begin(), entries.end());

  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> cg;
  cg.setTolerance(parameters.laplace_tolerance);
  cg.setMaxIterations(parameters.laplace_max_iterations);
  cg.compute(laplacian);
  const Eigen::VectorXd solution = cg.solve(rhs);
  if (cg.info() != Eigen::Success)
    fail<SolverError>("the Laplace field did not converge: relative residual {:.2e} after {} "
                      "CG iterations (limit {})",
                      cg.error(), cg.iterations(), parameters.laplace_max_iterations);

  Field field{ScalarGrid::like(mask, 1.0f)};
  for (std::size_t v = 0; v < mask.values.size(); ++v)
    if (zero[v] && mask.values[v])
      field.values.values[v] = 0.0f;
  for (Eigen::Index row = 0; row < n; ++row)
    field.values.values[voxel_of[row]] = static_cast<float>(solution[row]);
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
