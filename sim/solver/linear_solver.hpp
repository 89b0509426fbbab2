#pragma once
/// @brief Linear solves with the stiffness of the free DOFs, A = diag(m) + s K(x): a sparse
/// direct Cholesky (CHOLMOD) or the filtered, block-Jacobi preconditioned conjugate gradient
/// on element matrices (no global matrix).

#include "sim/solver/boundary_conditions.hpp"
#include "sim/solver/extra_potential.hpp"
#include "sim/solver/hyperelastic_body.hpp"

#include <Eigen/Core>

#include <memory>
#include <string>
#include <vector>

namespace ligsim::sim {

enum class LinearSolverKind { direct, pcg };

/// "direct" / "pcg"; throws InputError naming `where` otherwise.
LinearSolverKind parse_linear_solver(const std::string& text, const std::string& where);
std::string to_string(LinearSolverKind kind);

struct LinearSolveReport {
  /// False when the matrix proved indefinite (failed Cholesky, negative curvature in CG) or
  /// CG ran out of iterations.
  bool ok = true;
  bool indefinite = false;
  int iterations = 0;     ///< CG iterations (pcg, or direct with a lagged factor)
  int factorizations = 0; ///< sparse Cholesky factorisations (direct)
  double relative_residual = 0.0;
};

struct PcgSettings {
  double tolerance = 1e-6; ///< ||r|| / ||b|| to stop at
  int max_iterations = 10000;
};

class FilteredPcg;
class DirectCholesky;

class StiffnessSolver {
public:
  StiffnessSolver(const HyperelasticBody& body, const DofPartition& dofs, LinearSolverKind kind,
                  const PcgSettings& pcg);
  ~StiffnessSolver();
  StiffnessSolver(const StiffnessSolver&) = delete;
  StiffnessSolver& operator=(const StiffnessSolver&) = delete;

  LinearSolverKind kind() const { return m_kind; }

  /// Builds A = diag(mass) + stiffness_scale (K(x) + node blocks) (mass: one entry per free DOF,
  /// or empty for none; node blocks: an extra potential's Hessian), each element's K projected
  /// to positive semi-definite when `project`. Returns how many elements needed that
  /// projection. `x` must have no inverted element, unless `energy` is given: then it receives
  /// the body's energy (and `gradient`, when given, its gradient) as
  /// HyperelasticBody::energy_gradient() gives them, from the same pass where the solver allows,
  /// and an inverted element leaves A undefined.
  int prepare(const Eigen::VectorXd& x, bool project, double stiffness_scale = 1.0,
              const Eigen::VectorXd& mass = Eigen::VectorXd(),
              const std::vector<NodeBlock>& blocks = {}, BodyEnergy* energy = nullptr,
              Eigen::VectorXd* gradient = nullptr);

  /// Solves A y = b (free-DOF vectors). `y` holds the initial guess for CG.
  LinearSolveReport solve(const Eigen::VectorXd& b, Eigen::VectorXd& y);

  /// y = A x with the matrix of the last prepare() (free-DOF vectors).
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;

  /// Structural figures: matrix non-zeros (direct) or stored element matrices (pcg).
  std::size_t stored_values() const;

  /// The direct solver (null for pcg), for sharing its matrix and factor.
  DirectCholesky* direct() { return m_direct.get(); }

private:
  const HyperelasticBody& m_body;
  const DofPartition& m_dofs;
  LinearSolverKind m_kind;
  std::unique_ptr<DirectCholesky> m_direct;
  std::unique_ptr<FilteredPcg> m_pcg;
};

} // namespace ligsim::sim
