#pragma once
/// @brief The one Newton iteration of the solid solvers. At a fixed load factor t it minimises
///   Pi(x) = W(x) - t f.(x - X) + extra(x, t) + inertia(x) + damping(x)
/// over the free DOFs: W the body's strain energy, f the nodal loads, extra a contact barrier,
/// and, for a step of implicit Euler written as an incremental potential, the inertia
/// 1/2 sum w_i (x_i - y_i)^2 and Rayleigh's stiffness damping 1/2 c (x - s)^T K_s (x - s).
/// A quasi-static step has neither; an implicit Euler step (Baraff and Witkin's solve is its
/// first iteration) has both. One direction (element projection, saddle and shifted steps), one
/// line search, one convergence test, one report of what the iterations cost.

#include "sim/solver/boundary_conditions.hpp"
#include "sim/solver/extra_potential.hpp"
#include "sim/solver/hyperelastic_body.hpp"
#include "sim/solver/linear_solver.hpp"
#include "sim/solver/newton_convergence.hpp"
#include "sim/solver/tangent_inertia.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <optional>
#include <string>

namespace ligsim::sim {

/// When element stiffnesses are projected to positive semi-definite.
enum class PsdProjection {
  /// only for a Newton step whose matrix proved indefinite, and only where the unprojected
  /// Newton step (L D L^T, line search on the residual) makes no progress
  automatic,
  always,
  never, ///< an indefinite matrix fails the step (and triggers a cut-back)
};

std::string to_string(PsdProjection projection);

/// What Newton iterations cost and met; the solvers' step and frame reports carry it.
struct NewtonCounts {
  int iterations = 0;
  int linear_iterations = 0;     ///< CG iterations
  int factorizations = 0;        ///< sparse Cholesky factorisations
  int projected_elements = 0;    ///< element stiffness projections, summed over iterations
  int indefinite_iterations = 0; ///< iterations whose stiffness matrix was indefinite
  int line_search_backtracks = 0;
  int saddle_iterations = 0; ///< iterations by the unprojected (indefinite) Newton step
  /// iterations by the shifted Newton step (K + sigma D, a retry after a failed sub-step with an
  /// extra potential and an indefinite stiffness)
  int shifted_iterations = 0;
  double relative_residual = 0.0;
  /// Converged at the round-off floor (residual stagnating a hair above the tolerance);
  /// `floor` gives the figures.
  bool converged_at_floor = false;
  std::string floor;
};

/// What a solve's Newton iterations cost, summed over its steps, sub-steps or frames.
struct SolveCosts {
  int newton_iterations = 0;
  int linear_iterations = 0;  ///< CG iterations
  int factorizations = 0;     ///< sparse Cholesky factorisations
  int projected_elements = 0; ///< element stiffness projections
  void add(const NewtonCounts& counts)
  {
    newton_iterations += counts.iterations;
    linear_iterations += counts.linear_iterations;
    factorizations += counts.factorizations;
    projected_elements += counts.projected_elements;
  }
  void add(const SolveCosts& costs)
  {
    newton_iterations += costs.newton_iterations;
    linear_iterations += costs.linear_iterations;
    factorizations += costs.factorizations;
    projected_elements += costs.projected_elements;
  }
};

/// Whether `x` can start a solve of `dof_count` DOFs; if not, `failure` says why.
inline bool valid_start(const Eigen::VectorXd& x, int dof_count, std::string& failure)
{
  if (x.size() == dof_count && x.allFinite())
    return true;
  failure = "the initial positions are missing or not finite";
  return false;
}

/// The inertia of an implicit Euler step: 1/2 sum w_i (x_i - y_i)^2 over the free DOFs.
struct InertiaTerm {
  Eigen::VectorXd weight; ///< per free DOF, N/mm: (1 + h alpha) m / h^2
  Eigen::VectorXd target; ///< per free DOF, mm: x_start + h v / (1 + h alpha)
};

/// Rayleigh stiffness damping as a dissipation potential: 1/2 c (x - s)^T K_s (x - s) over the
/// free DOFs, K_s the projected stiffness at the step's start s, c = beta / h.
struct DampingTerm {
  double factor = 0.0;                    ///< c, 1/1
  const Eigen::SparseMatrix<double>* K_s; ///< lower triangle, free DOFs (not owned)
  Eigen::VectorXd start;                  ///< s, free DOFs
};

/// How a solver drives the iteration; the defaults are the quasi-static step's.
struct NewtonPolicy {
  int max_iterations = 30;
  /// Iterations made before the convergence test may stop (implicit Euler: its one solve).
  int min_iterations = 0;
  double residual_tolerance = 1e-8;
  /// The last step's energy change |alpha d.r| <= energy_tolerance * the first one's; 0 means
  /// the same value as residual_tolerance; NewtonConvergence::no_energy_test skips it.
  double energy_tolerance = 0.0;
  /// The supports' force the residual is measured against (empty: the reactions of the state
  /// itself; a wrong state's reactions are inflated, so implicit Euler gives the last frame's).
  std::optional<double> support_force_n;
  /// The unprojected Newton step (L D L^T) where the stiffness is indefinite and there is no
  /// extra potential: it converges quadratically to a saddle equilibrium.
  bool saddle_steps = true;
  /// The extra potential's Hessian blocks are projected before this iteration (0-based) and
  /// exact from it; the projection follows wherever the exact blocks make the matrix indefinite.
  int exact_extra_from = 0;
  /// After the first iteration, a matrix indefinite with the exact extra blocks fails the
  /// iteration (a shorter step is cheaper than Newton with projected blocks, which converges
  /// only linearly on nodes sliding over an obstacle) instead of projecting them.
  bool indefinite_exact_extra_fails = false;
  /// How a step is accepted: by an Armijo decrease of Pi (false: any admissible fraction, the
  /// largest of 1, 1/2, 1/4, ..., up to admissible_backtracks halvings).
  bool energy_decrease = true;
  int admissible_backtracks = 10;
  bool verbose = false; ///< one line per iteration on stderr
};

enum class NewtonOutcome { converged, out_of_iterations, failed };

class NewtonEngine {
public:
  struct Evaluation {
    BodyEnergy body;
    /// dW/dx - t f + d extra/dx, full DOFs: its prescribed entries are the reactions.
    Eigen::VectorXd gradient;
    Eigen::VectorXd free_gradient;   ///< dPi/dx on the free DOFs (inertia and damping included)
    double total_energy = 0.0;       ///< Pi, N mm
    bool extra_inadmissible = false; ///< the extra potential is infinite
  };

  /// `external`: the nodal forces at t = 1 (flat, N); `tangent` (null: none) factorises the
  /// unprojected stiffness for saddle steps.
  NewtonEngine(const HyperelasticBody& body, const DofPartition& dofs,
               const Eigen::VectorXd& external, StiffnessSolver& linear, TangentInertia* tangent,
               PsdProjection projection);

  void set_extra_potential(const ExtraPotential* potential) { m_extra = potential; }
  const ExtraPotential* extra_potential() const { return m_extra; }
  /// The inertia and damping of an implicit Euler step (null: a quasi-static step; not owned).
  void set_incremental_terms(const InertiaTerm* inertia, const DampingTerm* damping);
  /// Shifted Newton steps (K + sigma D) until switched off: a retry of a sub-step whose
  /// projected steps crawled along a buckling mode.
  void set_shifted(bool shifted);
  bool shifted() const { return m_shifted; }

  /// Minimises Pi at load factor t from x (admissible: its energy finite). `current` holds the
  /// evaluation at x on entry (empty: made here) and at the returned x on exit.
  NewtonOutcome minimise(Eigen::VectorXd& x, double t, const NewtonPolicy& policy,
                         NewtonCounts& counts, std::optional<Evaluation>& current);

  void evaluate(const Eigen::VectorXd& x, double t, Evaluation& out) const;
  /// The Newton direction for the free DOFs with right-hand side `rhs` at (x, t); handles the
  /// projections. With `allow_saddle`, an indefinite stiffness gives the unprojected Newton step
  /// (`saddle` set). False (failure() set) when none is found.
  bool direction(const Eigen::VectorXd& x, double t, const Eigen::VectorXd& rhs,
                 const NewtonPolicy& policy, int iteration, Eigen::VectorXd& direction,
                 NewtonCounts& counts, bool allow_saddle, bool& saddle);
  /// |free gradient| / max(|load at t|, the supports' force, force floor).
  double relative_residual(const Evaluation& at, double t, const NewtonPolicy& policy) const;
  /// "element 12 inverts (J = -0.1)", or the contact surface a node would cross.
  std::string describe_inversion(const BodyEnergy& energy) const;
  /// The norm of the reactions of `gradient` (its prescribed entries), N.
  double reaction_norm(const Eigen::VectorXd& gradient) const;

  const std::string& failure() const { return m_failure; }
  void set_failure(std::string failure) { m_failure = std::move(failure); }
  double force_floor() const { return m_force_floor; }

private:
  /// Newton direction of the unprojected K(x) and exact extra Hessian, shifted by sigma D (D a
  /// stiffness scale per DOF: m_shift_unit plus the extra Hessian's diagonal) where that is
  /// indefinite, sigma growing tenfold until the matrix is positive definite and the step goes
  /// downhill. Unlike the element-wise projection, it keeps the negative curvature of a buckling
  /// mode, so past a bifurcation the energy descent follows the mode instead of crawling.
  bool shifted_direction(const Eigen::VectorXd& x, double t, const Eigen::VectorXd& rhs,
                         Eigen::VectorXd& direction, NewtonCounts& counts);
  /// The matrix of Pi's Hessian at x (element projection `project`) with `blocks`; with `body`,
  /// the same pass gives its body energy and gradient (complete() finishes the evaluation).
  int prepare(const Eigen::VectorXd& x, bool project, const std::vector<NodeBlock>& blocks,
              const Eigen::VectorXd& shift = Eigen::VectorXd(), Evaluation* body = nullptr);
  /// The evaluation at x from its body energy and gradient: loads, extra, inertia, damping.
  void complete(const Eigen::VectorXd& x, double t, Evaluation& out) const;
  /// Backtracking along `direction` from `current` at x: on Pi (Armijo, or any admissible
  /// fraction), or for a saddle step on the residual norm. Sets x_trial, trial, alpha; false
  /// when no step is acceptable (failure() says why for an energy search).
  bool line_search(const Eigen::VectorXd& x, const Evaluation& current,
                   const Eigen::VectorXd& direction, bool saddle, double t,
                   const NewtonPolicy& policy, NewtonCounts& counts, Eigen::VectorXd& x_trial,
                   Evaluation& trial, double& alpha);
  /// Pi's energy round-off scale at the state: |W| + |work| + mu V.
  double energy_scale(const Eigen::VectorXd& x, const Evaluation& at, double t) const;

  const HyperelasticBody& m_body;
  const DofPartition& m_dofs;
  const Eigen::VectorXd& m_external;
  Eigen::VectorXd m_rest;
  StiffnessSolver& m_linear;
  TangentInertia* m_tangent;
  PsdProjection m_projection;
  const ExtraPotential* m_extra = nullptr;
  const InertiaTerm* m_inertia = nullptr;
  const DampingTerm* m_damping = nullptr;
  double m_force_floor = 0.0; ///< absolute residual below which any state converges
  double m_energy_unit = 0.0; ///< mu V: the scale of energy round-off, N mm
  double m_length_mm = 0.0;   ///< the body's size
  /// mu times the lumped rest volume per free DOF over the mean element size squared, N/mm: the
  /// unit of the shifted Newton step's diagonal
  Eigen::VectorXd m_shift_unit;
  /// A matrix prepared with the first evaluation of a solve, for its first direction.
  struct Prepared {
    std::vector<NodeBlock> blocks;
    int projected_elements = 0;
  };
  std::optional<Prepared> m_prepared;
  bool m_shifted = false;
  double m_shift = 0.0; ///< the last sigma that gave a descent direction
  std::string m_failure;
};

} // namespace ligsim::sim
