#pragma once
/// @brief The unprojected tangent stiffness of the free DOFs factorised as L D L^T (no
/// pivoting): Newton directions where the stiffness is indefinite (saddle equilibria, as past a
/// bifurcation), its inertia (Sylvester: the negative entries of D count the negative
/// eigenvalues) and the eigenpair nearest zero by inverse iteration (the buckling mode).

#include "sim/solver/boundary_conditions.hpp"
#include "sim/solver/hyperelastic_body.hpp"
#include "sim/solver/stiffness_matrix.hpp"

#include <Eigen/CholmodSupport>
#include <Eigen/Core>

#include <string>
#include <vector>

namespace ligsim::sim {

/// The eigenpair of the tangent stiffness nearest zero and what it means for the load path.
struct StabilityMode {
  int negative_eigenvalues = 0;
  double eigenvalue = 0.0; ///< N/mm, of the free-DOF stiffness
  /// |phi . f| / (|phi| |f|): near 0 the mode is orthogonal to the load (a bifurcation), near 1
  /// it is the load's own direction (a limit point).
  double load_alignment = 0.0;
  int peak_node = -1; ///< the node that moves most in the mode
  Eigen::Vector3d peak_direction = Eigen::Vector3d::Zero(); ///< its unit direction
  /// "bifurcation" or "limit point"
  std::string kind() const;
  /// One line: kind, eigenvalue, negative count, node and direction.
  std::string describe() const;
};

/// CHOLMOD's simplicial L D L^T (no pivoting, so indefinite matrices factorise unless a pivot
/// is zero), with access to D.
class CholmodLdlt : public Eigen::CholmodSimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> {
public:
  CholmodLdlt();
  /// The pivots D of the last factorisation (empty without one).
  Eigen::VectorXd pivots() const;
};

class TangentInertia {
public:
  TangentInertia(const HyperelasticBody& body, const DofPartition& dofs);

  /// Assembles and factorises the unprojected K(x); false when a pivot is zero or not finite.
  bool factorize(const Eigen::VectorXd& x);
  /// Negative eigenvalues of the last factorised K.
  int negative_eigenvalues() const;
  /// Solves K y = b with the last factor (free-DOF vectors).
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  /// Inverse iteration from a fixed start: the eigenpair of the last K nearest zero.
  /// `load` (free-DOF external force at full load) classifies the mode.
  StabilityMode lowest_mode(const Eigen::VectorXd& load) const;

private:
  const HyperelasticBody& m_body;
  const DofPartition& m_dofs;
  StiffnessMatrix m_stiffness;
  CholmodLdlt m_ldlt;
  Eigen::VectorXd m_pivots;
  std::vector<Matrix12d> m_chunk;
  bool m_analyzed = false;
  bool m_ok = false;
};

} // namespace ligsim::sim
