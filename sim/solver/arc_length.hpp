#pragma once
/// @brief Path following through limit points: Riks' arc-length continuation (normal-plane
/// corrector, bordered Newton solves with the unprojected tangent factorised as L D L^T) for a
/// dead load pattern f scaled by the load factor lambda, g(u) = lambda f. Load control stops at a
/// limit point (past it no equilibrium is near); arc length turns round it, locates it and
/// follows the path until lambda reaches its target. Where the scene allows: supports that do
/// not move, nodal forces, no contact.
///
/// Its corrector iterates on its own rather than through NewtonEngine: it solves the residual
/// and the arc-length constraint together for (u, lambda), a bordered system with no energy to
/// descend, where the engine minimises a potential at a fixed load factor with a line search on
/// it. The tests drive it with a von Mises truss through the abstract EquilibriumSystem.

#include "sim/solver/boundary_conditions.hpp"
#include "sim/solver/hyperelastic_body.hpp"
#include "sim/solver/stiffness_matrix.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <string>
#include <vector>

namespace ligsim::sim {

/// Equilibrium g(u) = lambda f of n unknowns u.
class EquilibriumSystem {
public:
  virtual ~EquilibriumSystem() = default;
  virtual Eigen::Index size() const = 0;
  /// Internal force g(u), N; false where u is inadmissible (an element inverts).
  virtual bool internal_force(const Eigen::VectorXd& u, Eigen::VectorXd& g) const = 0;
  /// Lower triangle (with the diagonal) of the tangent dg/du at an admissible u, N/mm.
  virtual void tangent(const Eigen::VectorXd& u, Eigen::SparseMatrix<double>& K) const = 0;
  /// The load pattern f (lambda = 1), N.
  virtual const Eigen::VectorXd& load() const = 0;
};

/// A body under constraints and nodal loads; u are the positions of the free DOFs, mm.
/// InputError where a prescribed component moves with the load factor (use the StaticSolver).
class BodyEquilibrium : public EquilibriumSystem {
public:
  BodyEquilibrium(const HyperelasticBody& body, const BoundaryConditions& conditions);

  Eigen::Index size() const override { return m_dofs.free_count(); }
  bool internal_force(const Eigen::VectorXd& u, Eigen::VectorXd& g) const override;
  void tangent(const Eigen::VectorXd& u, Eigen::SparseMatrix<double>& K) const override;
  const Eigen::VectorXd& load() const override { return m_load; }

  /// The free DOFs of the rest shape.
  Eigen::VectorXd rest_unknowns() const;
  /// All positions (flat, mm) with the free DOFs taken from u.
  Eigen::VectorXd positions(const Eigen::VectorXd& u) const;

private:
  const HyperelasticBody& m_body;
  DofPartition m_dofs;
  Eigen::VectorXd m_rest;
  Eigen::VectorXd m_load;
  mutable StiffnessMatrix m_stiffness;
};

struct ArcLengthSettings {
  double first_load_increment = 0.05; ///< the first step's load factor increment: sets the arc
  double max_arc_growth = 4.0;        ///< the arc may grow to this multiple of the first one ...
  double min_arc_fraction = 1e-6;     ///< ... or shrink to this fraction before giving up
  int desired_iterations = 4;         ///< the arc grows after easier steps, shrinks after harder
  int max_iterations = 25;            ///< Newton iterations per step before the arc is halved
  int max_steps = 1000;
  /// Converged when |g(u) - lambda f| <= residual_tolerance |f|.
  double residual_tolerance = 1e-10;
  double target_load_factor = 1.0;
};

/// One converged point of the path.
struct PathPoint {
  double load_factor = 0.0;
  double arc = 0.0;             ///< accumulated (scaled) arc length
  int negative_eigenvalues = 0; ///< of the tangent at the point (negative pivots of L D L^T)
  int iterations = 0;
};

/// A change of the tangent's inertia between two path points.
struct CriticalPoint {
  /// "limit point" (the load factor turns: a maximum or minimum along the path) or
  /// "bifurcation" (the inertia changes while the load factor keeps its direction).
  std::string kind;
  /// Limit point: the extremum of the parabola through the path points around it;
  /// bifurcation: the middle of its bracket.
  double load_factor = 0.0;
  double bracket_from = 0.0; ///< load factors of the path points around it
  double bracket_to = 0.0;
  int step = 0; ///< the path point at (limit) or after (bifurcation) it
};

struct ArcLengthResult {
  bool reached = false; ///< equilibrium at the target load factor found
  std::string failure;  ///< why not
  std::vector<PathPoint> path;
  std::vector<CriticalPoint> critical_points;
  int newton_iterations = 0;
  int cutbacks = 0;
};

/// Follows the path from u (equilibrium at lambda = 0, usually the rest shape) until lambda
/// reaches the target; u then holds that equilibrium (the last converged one on failure).
ArcLengthResult follow_path(const EquilibriumSystem& system, Eigen::VectorXd& u,
                            const ArcLengthSettings& settings = {});

} // namespace ligsim::sim
