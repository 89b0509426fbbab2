#include "sim/material/quadratic_tet_element.hpp"

#include "common/error.hpp"

#include <algorithm>
#include <limits>

namespace ligsim::sim {

void evaluate_quadratic_tet(const WeissMaterial& material, const QuadraticTetRows& Q,
                            const QuadraticTetShape& shape, const Eigen::Vector3d* fibers,
                            std::size_t fiber_count, ElementNeeds needs,
                            QuadraticTetEvaluation& out)
{
  const std::size_t point_count = shape.points.size();
  if (material.has_fibers() && fiber_count != 1 && fiber_count != point_count)
    fail("the element has {} fiber vectors for {} quadrature points", fiber_count, point_count);
  out.inverted = false;
  out.J = std::numeric_limits<double>::infinity();
  out.energy = 0.0;
  if (needs != ElementNeeds::energy)
    out.gradient.setZero();
  if (needs == ElementNeeds::hessian)
    out.hessian.setZero();
  const Eigen::Vector3d no_fiber = Eigen::Vector3d::Zero();
  QuadraticTetEvaluation point;
  for (std::size_t q = 0; q < point_count; ++q) {
    const Eigen::Vector3d& fiber = fiber_count == 0 ? no_fiber : fibers[fiber_count == 1 ? 0 : q];
    material.evaluate_at_point<10>(Q, shape.points[q].G, shape.points[q].weight, fiber, needs,
                                   point);
    out.J = std::min(out.J, point.J);
    if (point.inverted) {
      out.inverted = true;
      out.energy = std::numeric_limits<double>::infinity();
      return;
    }
    out.energy += point.energy;
    if (needs != ElementNeeds::energy)
      out.gradient += point.gradient;
    if (needs == ElementNeeds::hessian)
      out.hessian += point.hessian;
  }
}

} // namespace ligsim::sim
