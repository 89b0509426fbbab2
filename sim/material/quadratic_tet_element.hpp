#pragma once
/// @brief The Weiss material integrated over one 10-node tet: the sum of its quadrature points.

#include "sim/material/weiss_material.hpp"
#include "sim/mesh/quadratic_tet.hpp"

#include <Eigen/Core>

#include <cstddef>

namespace ligsim::sim {

using QuadraticTetEvaluation = NodalEvaluation<10>;

/// Evaluates the element with nodes `Q` (mm). `fibers` points to `fiber_count` fiber vectors a
/// (|a| = 1 + in-situ strain): one for each of the shape's quadrature points, in their order,
/// or one for all; they are ignored when the material has no fibers. The element is inverted
/// when J is not positive at one of its points; `out.J` is the smallest J over them.
void evaluate_quadratic_tet(const WeissMaterial& material, const QuadraticTetRows& Q,
                            const QuadraticTetShape& shape, const Eigen::Vector3d* fibers,
                            std::size_t fiber_count, ElementNeeds needs,
                            QuadraticTetEvaluation& out);

} // namespace ligsim::sim
