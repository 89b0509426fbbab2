#pragma once
/// @brief The Newton iteration's keys, listed once: a flexion config's [static] and a scene's
/// [solver] both hold them. visit(key, member) or visit(key, choice(...)), as the configs' other
/// key lists do.

#include "common/config_choice.hpp"
#include "sim/solver/static_solver.hpp"

namespace ligsim::sim {

template <class N, class Visit> void visit_newton_iteration(N& n, Visit&& visit)
{
  visit("residual_tolerance", n.residual_tolerance);
  visit("max_iterations", n.max_iterations);
  visit("max_cutbacks", n.max_cutbacks);
  visit("max_substeps", n.max_substeps);
  visit("verbose", n.verbose);
  visit("linear_solver",
        choice(n.linear_solver, to_string, {LinearSolverKind::direct, LinearSolverKind::pcg}));
}

} // namespace ligsim::sim
