#pragma once
/// @brief Sparse L D L^T (L unit lower, D diagonal, no pivoting) in supernodes: CHOLMOD's
/// symbolic analysis (METIS ordering, relaxed supernodes) once per pattern, then a left-looking
/// numeric factorisation with dense BLAS blocks. It factorises indefinite matrices unless a pivot
/// is zero, so one factorisation gives the solve and the inertia (Sylvester: the negative pivots
/// count the negative eigenvalues), at the speed of the supernodal Cholesky.

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <cstddef>
#include <memory>
#include <vector>

namespace ligsim::sim {

/// The symbolic analysis of one pattern: elimination order, supernodes and where everything
/// goes. Shared by every factor of the same pattern (the last one analysed is kept, so solvers
/// made one after another on one mesh analyse it once).
struct SupernodalSymbolic {
  std::vector<int> pattern_outer; ///< the analysed pattern (CSC of the lower triangle)
  std::vector<int> pattern_inner;
  std::vector<int> perm;      ///< elimination order: row perm[k] of A is eliminated k-th
  std::vector<int> super;     ///< first column of each supernode, #supernodes + 1
  std::vector<int> row_start; ///< start of each supernode's rows in `rows`, #supernodes + 1
  std::vector<std::ptrdiff_t> value_start; ///< start of each supernode's block in the values
  std::vector<int> rows;                   ///< row indices (elimination order) per supernode
  std::vector<int> column_super;           ///< supernode of each column
  std::vector<std::ptrdiff_t> scatter;     ///< position in the values of each entry of A
  std::size_t value_count = 0;             ///< entries of L, explicit zeros included
  std::size_t scratch_size = 1; ///< doubles of scaled panels and blocks a factorisation needs
  int tallest = 1;              ///< rows of the tallest supernode
  double flops = 0.0;
  double cost = 0.0; ///< see SupernodalLdlt::factorization_cost()

  int size() const { return static_cast<int>(perm.size()); }
  int supernodes() const { return static_cast<int>(super.size()) - 1; }
  bool matches(const Eigen::SparseMatrix<double>& lower) const;
};

class SupernodalLdlt {
public:
  /// Symbolic analysis of the pattern of `lower` (the lower triangle with the diagonal, CSC,
  /// compressed), or the analysis of the same pattern made last. Later factorisations must use
  /// the same pattern.
  void analyze(const Eigen::SparseMatrix<double>& lower);
  bool analyzed() const { return m_symbolic != nullptr; }
  /// The symbolic analysis in use (requires analyze()).
  const SupernodalSymbolic& symbolic() const { return *m_symbolic; }

  /// Numeric factorisation; false when a pivot is zero or not finite (the factor is then
  /// unusable). Requires analyze() on the same pattern.
  bool factorize(const Eigen::SparseMatrix<double>& lower);
  /// The last factorize() succeeded.
  bool ok() const { return m_ok; }

  /// Solves A y = b with the factor (vectors in the matrix's numbering), in single precision
  /// after to_single_precision().
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  /// Keeps L in single precision only, until the next factorize(): half the memory, and half
  /// the memory traffic of a solve (a preconditioner's accuracy; the pivots stay double).
  void to_single_precision();
  bool single_precision() const { return !m_single.empty(); }
  /// Pivots D of the last successful factorisation, in elimination order (empty otherwise).
  const Eigen::VectorXd& pivots() const { return m_pivots; }
  /// Negative pivots: the matrix's negative eigenvalues (-1 without a factor).
  int negative_pivots() const { return m_ok ? m_negative : -1; }
  /// Floating-point operations of one factorisation (multiply-adds counted as two).
  double factorization_flops() const { return m_symbolic->flops; }
  /// Stored entries of L (with the explicit zeros of relaxed supernodes).
  std::size_t factor_entries() const { return m_symbolic->value_count; }
  /// Estimated time of one factorisation in units of reading one factor entry in a solve (a
  /// solve costs about factor_entries()): from the flops, the scattered updates and their count.
  double factorization_cost() const { return m_symbolic->cost; }

private:
  /// Adds the update of descendant supernode d into supernode s (d's rows [first, last) are
  /// columns of s).
  void apply_descendant(int d, int first, int last, int s);
  /// Dense L D L^T of supernode s's columns (its diagonal block and the rows below).
  bool factorize_supernode(int s);

  std::shared_ptr<const SupernodalSymbolic> m_symbolic;
  std::vector<double> m_values; ///< column-major blocks, #rows x #columns each
  std::vector<float> m_single;  ///< the same in single precision (m_values then empty)
  Eigen::VectorXd m_pivots;
  bool m_ok = false;
  int m_negative = 0;

  // Workspace of the numeric factorisation.
  std::vector<int> m_local_row; ///< row (elimination order) -> row within the current supernode
  std::vector<int> m_head;      ///< descendants waiting to update each supernode (linked list)
  std::vector<int> m_next;
  std::vector<int> m_position; ///< each supernode's next row to update with
  std::vector<double> m_update;
  std::vector<double> m_scaled;
};

} // namespace ligsim::sim
