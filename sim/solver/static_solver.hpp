#pragma once
/// @brief Quasi-static equilibrium: Newton's method with a line search on the total energy
/// (on the residual norm where the stiffness is indefinite and the equilibrium a saddle),
/// automatic sub-stepping inside the user's load steps, convergence on the relative residual
/// and the energy or at the round-off floor, and a limit-point / bifurcation diagnostic.

#include "sim/solver/boundary_conditions.hpp"
#include "sim/solver/extra_potential.hpp"
#include "sim/solver/hyperelastic_body.hpp"
#include "sim/solver/linear_solver.hpp"
#include "sim/solver/newton_engine.hpp"
#include "sim/solver/tangent_inertia.hpp"

#include <Eigen/Core>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace ligsim::sim {

struct NewtonSettings {
  int load_steps = 10; ///< equal load steps from 0 to 1, unless load_factors is given
  /// The load factors of the reported steps, increasing, in [0, 1]; a step at the current load
  /// factor (a leading 0) is solved in place: equilibrium before anything moves. Empty: uniform.
  std::vector<double> load_factors;
  int max_iterations = 30; ///< per load step
  /// Converged when ||r_free|| <= residual_tolerance * max(||f_ext||, ||reactions||) ...
  double residual_tolerance = 1e-8;
  /// ... and the last step's energy change |alpha d.r| <= energy_tolerance * the first one's;
  /// 0 means the same value as residual_tolerance.
  double energy_tolerance = 0.0;
  LinearSolverKind linear_solver = LinearSolverKind::direct;
  PcgSettings pcg;
  PsdProjection projection = PsdProjection::automatic;
  int max_cutbacks = 10; ///< consecutive halvings of a sub-step before giving up
  /// sub-steps of one load step before giving up where one fails (a load factor that crawls
  /// forward in slivers between failures never exhausts max_cutbacks)
  int max_substeps = 100;
  bool verbose = false; ///< one line per Newton iteration on stderr
};

/// What one nominal load step cost and reached (its Newton counts summed over its sub-steps).
struct StepReport : NewtonCounts {
  int step = 0; ///< 1-based
  double load_factor = 0.0;
  bool converged = false;
  int substeps = 0;
  int cutbacks = 0;
  /// Negative eigenvalues of the tangent stiffness at the converged state, counted where a
  /// step met an indefinite stiffness (0 otherwise): > 0 is an unstable equilibrium.
  int negative_eigenvalues = 0;
  std::string instability;       ///< the mode, where negative_eigenvalues > 0
  double strain_energy_mj = 0.0; ///< N mm
  double min_j = 1.0;
  int min_j_element = -1;
  double wall_s = 0.0;
};

struct StaticResult : SolveCosts {
  bool converged = false;
  std::string failure; ///< why it stopped, naming the element where one is to blame
  /// How a failure stopped: "failed step" (no convergence), or a critical point of the path met
  /// between the last converged load factor and the failed one: "limit point" (the mode moves
  /// along the load) or "bifurcation" (the mode is orthogonal to it).
  std::string stop_kind;
  std::optional<StabilityMode> critical_mode;
  double critical_load_factor = 0.0; ///< the last converged load factor before it
  std::vector<StepReport> steps;
  int cutbacks = 0;
  double wall_s = 0.0;
};

class StaticSolver {
public:
  /// Called after every converged nominal step with the positions and the full residual
  /// dE/dx - f_ext (its prescribed entries are the reactions).
  using StepCallback = std::function<void(const StepReport&, const Eigen::VectorXd& x,
                                          const Eigen::VectorXd& residual)>;

  StaticSolver(const HyperelasticBody& body, const BoundaryConditions& conditions,
               const NewtonSettings& settings);

  /// Drives the load factor from 0 to 1 starting at `x` (flat positions, mm, usually the rest
  /// shape). Never throws on divergence: the result says what failed, `x` holds the last
  /// converged state.
  StaticResult solve(Eigen::VectorXd& x, const StepCallback& on_step = {});

  /// Adds `potential` (not owned; null: none) to the energy: its gradient enters the residual,
  /// its Hessian blocks the Newton matrix, its step bound the line search.
  void set_extra_potential(const ExtraPotential* potential)
  {
    m_engine.set_extra_potential(potential);
  }

  /// Guesses of the steps' equilibria (starts[k] for step k + 1; an empty one: none), such as
  /// a free knee's search found them: a step is solved from its guess at once, and along the
  /// path from the last state where the guess does not converge.
  void set_step_starts(std::vector<Eigen::VectorXd> starts) { m_step_starts = std::move(starts); }

  const DofPartition& dofs() const { return m_dofs; }
  std::size_t linear_solver_storage() const { return m_linear.stored_values(); }

private:
  /// The load factors of the reported steps.
  std::vector<double> step_targets() const;
  /// Brings the converged state to load factor t1; false (with m_failure set) when it cannot.
  bool advance(Eigen::VectorXd& x, double t1, StepReport& report);
  /// Moves the prescribed DOFs to their targets at t1, the free ones by the linear predictor.
  bool move_prescribed(Eigen::VectorXd& x, double t1, StepReport& report);
  /// The eigenpair nearest zero of the tangent at x, if it can be factorised.
  std::optional<StabilityMode> stability_mode(const Eigen::VectorXd& x);

  const HyperelasticBody& m_body;
  const BoundaryConditions& m_conditions;
  NewtonSettings m_settings;
  DofPartition m_dofs;
  Eigen::VectorXd m_external; ///< at load factor 1
  StiffnessSolver m_linear;
  TangentInertia m_tangent;
  NewtonEngine m_engine;
  NewtonPolicy m_policy;
  std::vector<int> m_boundary_elements; ///< elements with a prescribed DOF
  std::string m_failure;
  double m_converged_t = 0.0; ///< load factor of the last converged state
  std::vector<Eigen::VectorXd> m_step_starts;
};

} // namespace ligsim::sim
