#pragma once
/// @brief Sparse Cholesky (CHOLMOD, supernodal) of the assembled free-DOF matrix, with a lagged
/// factorisation: a factor of an earlier matrix preconditions CG on the current one, and the
/// matrix is refactorised only when that stops paying off. The pattern is analysed once.

#include "sim/solver/extra_potential.hpp"
#include "sim/solver/linear_solver.hpp"
#include "sim/solver/stiffness_matrix.hpp"

#include <Eigen/CholmodSupport>

#include <vector>

namespace ligsim::sim {

class HyperelasticBody;

class DirectCholesky {
public:
  DirectCholesky(const HyperelasticBody& body, const DofPartition& dofs);

  /// Assembles A = diag(mass) + scale (K(x) + node blocks); returns the projected element count.
  int prepare(const HyperelasticBody& body, const Eigen::VectorXd& x, bool project, double scale,
              const Eigen::VectorXd& mass, const std::vector<NodeBlock>& blocks);

  /// Solves A y = b: exactly with a fresh factor, else by CG preconditioned with the lagged one,
  /// refactorising when CG is slow. Reports an indefinite A (failed factorisation or negative
  /// curvature on a fresh factor).
  LinearSolveReport solve(const Eigen::VectorXd& b, Eigen::VectorXd& y);

  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const { m_stiffness.multiply(x, y); }
  std::size_t stored_values() const { return static_cast<std::size_t>(m_stiffness.nonzeros()); }
  int factorizations() const { return m_factorizations; }

private:
  bool factorize();
  /// CG on A preconditioned by the current factor; false when it needs more than `limit`
  /// iterations or meets negative curvature.
  bool lagged_cg(const Eigen::VectorXd& b, Eigen::VectorXd& y, int limit,
                 LinearSolveReport& report);

  StiffnessMatrix m_stiffness;
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> m_cholesky;
  std::vector<Matrix12d> m_chunk;
  bool m_analyzed = false;
  bool m_has_factor = false;   ///< a factor of some earlier A exists
  bool m_factor_fresh = false; ///< the factor is of the current A
  bool m_refactor_next = false;
  int m_factorizations = 0;
};

} // namespace ligsim::sim
