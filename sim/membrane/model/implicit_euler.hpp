#pragma once
/// @brief Implicit Euler for the membrane, solved matrix-free by a Jacobi-preconditioned
/// conjugate gradient (no global matrix is assembled, so topology changes cost nothing here).
///
/// One linearised step (Baraff and Witkin 1998) with Rayleigh damping D = a M + b K:
///   ((1 + h a) M + (h b + h^2) K) dv = h (f(x) + f_ext - a M v - (b + h) K v),
///   v += dv, x += h v.
/// Nodes with a prescribed velocity take dv = v_prescribed - v; CG runs on the free ones, warm
/// started from the previous step's dv.

#include "sim/membrane/mesh/membrane_mesh.hpp"
#include "sim/membrane/model/corotational_elements.hpp"

#include <vector>

namespace ligsim::membrane {

struct SolverSettings {
  double time_step_s = 1e-3;
  double mass_damping_per_s = 0.0;  ///< a
  double stiffness_damping_s = 0.0; ///< b
  double cg_tolerance = 1e-6;       ///< on the residual, relative to the right-hand side
  int cg_max_iterations = 200;
};

/// Throws InputError naming `where` for a non-positive time step or tolerance, negative
/// damping, or fewer than one CG iteration.
void validate(const SolverSettings& settings, const char* where);

struct SolveReport {
  int iterations = 0;
  double relative_residual = 0.0;
};

class ImplicitEuler {
public:
  explicit ImplicitEuler(const SolverSettings& settings)
      : m_settings(settings)
  {
  }

  /// Advances `mesh` by one time step under `external_forces` (N, #nodes). Updates the
  /// elements' rotations and stresses to the start of the step. Throws SolverError if a value
  /// turns non-finite.
  SolveReport step(MembraneMesh& mesh, CorotationalElements& elements,
                   const std::vector<Vec2>& external_forces);

  const SolverSettings& settings() const { return m_settings; }

private:
  /// out = A p on the free nodes, 0 on prescribed ones.
  void apply_system(const MembraneMesh& mesh, const CorotationalElements& elements,
                    const std::vector<Vec2>& p, std::vector<Vec2>& out);

  SolverSettings m_settings;
  // Scratch vectors, kept to avoid reallocating every step.
  std::vector<Vec2> m_force, m_rhs, m_diagonal, m_dv, m_residual, m_search, m_product, m_z;
};

} // namespace ligsim::membrane
