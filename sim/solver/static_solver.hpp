#pragma once
/// @brief Quasi-static equilibrium: Newton's method with a line search on the total energy,
/// load stepping with automatic cut-back, convergence on the relative residual and the energy.

#include "sim/solver/boundary_conditions.hpp"
#include "sim/solver/extra_potential.hpp"
#include "sim/solver/hyperelastic_body.hpp"
#include "sim/solver/linear_solver.hpp"

#include <Eigen/Core>

#include <functional>
#include <string>
#include <vector>

namespace ligsim::sim {

/// When element stiffnesses are projected to positive semi-definite.
enum class PsdProjection {
  automatic, ///< only for a Newton step whose matrix proved indefinite
  always,
  never, ///< an indefinite matrix fails the step (and triggers a cut-back)
};

PsdProjection parse_psd_projection(const std::string& text, const std::string& where);
std::string to_string(PsdProjection projection);

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
  int max_cutbacks = 10; ///< halvings of one load step before giving up
  bool verbose = false;  ///< one line per Newton iteration on stderr
};

/// What one nominal load step cost and reached.
struct StepReport {
  int step = 0; ///< 1-based
  double load_factor = 0.0;
  bool converged = false;
  int iterations = 0; ///< Newton iterations, all sub-steps together
  int substeps = 0;
  int cutbacks = 0;
  int linear_iterations = 0;     ///< CG iterations
  int factorizations = 0;        ///< sparse Cholesky factorisations
  int projected_elements = 0;    ///< element stiffness projections, summed over iterations
  int indefinite_iterations = 0; ///< iterations whose stiffness matrix was indefinite
  int line_search_backtracks = 0;
  double relative_residual = 0.0;
  double strain_energy_mj = 0.0; ///< N mm
  double min_j = 1.0;
  int min_j_element = -1;
  double wall_s = 0.0;
};

struct StaticResult {
  bool converged = false;
  std::string failure; ///< why it stopped, naming the element where one is to blame
  std::vector<StepReport> steps;
  int newton_iterations = 0;
  int cutbacks = 0;
  int projected_elements = 0;
  int linear_iterations = 0;
  int factorizations = 0;
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
  void set_extra_potential(const ExtraPotential* potential) { m_extra = potential; }

  const DofPartition& dofs() const { return m_dofs; }
  std::size_t linear_solver_storage() const { return m_linear.stored_values(); }

private:
  struct Evaluation {
    BodyEnergy body;
    Eigen::VectorXd gradient;
    double total_energy = 0.0;       ///< strain energy minus the work of the external forces
    bool extra_inadmissible = false; ///< the extra potential is infinite
  };

  /// The load factors of the reported steps.
  std::vector<double> step_targets() const;
  /// Brings the converged state to load factor t1; false (with m_failure set) when it cannot.
  bool advance(Eigen::VectorXd& x, double t1, StepReport& report);
  /// Moves the prescribed DOFs to their targets at t1, the free ones by the linear predictor.
  bool move_prescribed(Eigen::VectorXd& x, double t1, StepReport& report);
  /// Newton direction for the free DOFs; handles projection. False when none is found.
  bool newton_direction(const Eigen::VectorXd& x, double t, const Eigen::VectorXd& rhs,
                        Eigen::VectorXd& direction, StepReport& report);
  void evaluate(const Eigen::VectorXd& x, double t, Evaluation& out) const;
  Eigen::VectorXd free_part(const Eigen::VectorXd& full) const;
  std::string describe_inversion(const BodyEnergy& energy) const;
  /// The free part of `direction` as a full-length vector (prescribed entries zero).
  Eigen::VectorXd full_part(const Eigen::VectorXd& direction) const;

  const HyperelasticBody& m_body;
  const BoundaryConditions& m_conditions;
  NewtonSettings m_settings;
  DofPartition m_dofs;
  Eigen::VectorXd m_rest;
  Eigen::VectorXd m_external; ///< at load factor 1
  StiffnessSolver m_linear;
  std::vector<int> m_boundary_elements; ///< elements with a prescribed DOF
  double m_force_floor = 0.0;           ///< absolute residual below which any state converges
  double m_energy_unit = 0.0;           ///< mu V: the scale of energy round-off, N mm
  std::string m_failure;
  const ExtraPotential* m_extra = nullptr;
  double m_converged_t = 0.0; ///< load factor of the last converged state
};

} // namespace ligsim::sim
