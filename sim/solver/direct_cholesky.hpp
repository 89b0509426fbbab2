#pragma once
/// @brief Sparse direct solves of the assembled free-DOF matrix: supernodal L D L^T (no
/// pivoting: a positive definite matrix factorises as with Cholesky, an indefinite one reveals
/// its inertia), with a lagged factorisation: a positive definite factor of an earlier matrix
/// preconditions CG on the current one, and the matrix is refactorised when the CG iterations
/// spent since the last factorisation would have paid for a new one. The pattern is analysed
/// once.

#include "sim/solver/extra_potential.hpp"
#include "sim/solver/linear_solver.hpp"
#include "sim/solver/stiffness_matrix.hpp"
#include "sim/solver/supernodal_ldlt.hpp"

#include <vector>

namespace ligsim::sim {

class HyperelasticBody;

class DirectCholesky {
public:
  DirectCholesky(const HyperelasticBody& body, const DofPartition& dofs);

  /// Assembles A = diag(mass) + scale (K(x) + node blocks); returns the projected element count.
  /// `energy` and `gradient` (either may be null) receive the body's energy and gradient from
  /// the same pass (see StiffnessMatrix::add_elements).
  int prepare(const HyperelasticBody& body, const Eigen::VectorXd& x, bool project, double scale,
              const Eigen::VectorXd& mass, const std::vector<NodeBlock>& blocks,
              BodyEnergy* energy = nullptr, Eigen::VectorXd* gradient = nullptr);

  /// Solves A y = b: exactly with a fresh factor, else by CG preconditioned with the lagged one,
  /// refactorising when CG is slow. Reports an indefinite A (negative pivots, a zero pivot, or
  /// negative curvature on a fresh factor).
  LinearSolveReport solve(const Eigen::VectorXd& b, Eigen::VectorXd& y);

  /// Factorises the current A now; false when a pivot is zero or not finite.
  bool factorize();
  /// Whether the current factor is of the unprojected K(x) alone (scale 1, no mass, no node
  /// blocks), at exactly these positions.
  bool holds_tangent(const Eigen::VectorXd& x) const;
  /// The factor of the current A (valid after a successful factorize()).
  const SupernodalLdlt& factor() const { return m_ldlt; }

  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const { m_stiffness.multiply(x, y); }
  std::size_t stored_values() const { return static_cast<std::size_t>(m_stiffness.nonzeros()); }
  int factorizations() const { return m_factorizations; }

private:
  /// CG on A preconditioned by the current factor; false when it would need more iterations
  /// than a factorisation is worth or meets negative curvature.
  bool lagged_cg(const Eigen::VectorXd& b, Eigen::VectorXd& y, LinearSolveReport& report);

  StiffnessMatrix m_stiffness;
  SupernodalLdlt m_ldlt;
  /// CG iterations that cost about one factorisation: the budget of the lagged factor.
  int m_iteration_budget = 0;
  int m_lagged_iterations = 0; ///< spent since the last factorisation
  bool m_has_factor = false;   ///< a positive definite factor of some earlier A exists
  bool m_factor_fresh = false; ///< the factor is of the current A
  bool m_refactor_next = false;
  bool m_plain_tangent = false; ///< A is the unprojected K(m_tangent_x) alone
  Eigen::VectorXd m_tangent_x;
  int m_factorizations = 0;
};

} // namespace ligsim::sim
