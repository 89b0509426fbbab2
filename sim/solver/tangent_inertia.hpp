#pragma once
/// @brief The unprojected tangent stiffness of the free DOFs factorised as L D L^T (no
/// pivoting, supernodal): Newton directions where the stiffness is indefinite (saddle equilibria,
/// as past a bifurcation), its inertia (Sylvester: the negative entries of D count the negative
/// eigenvalues) and the eigenpair nearest zero by inverse iteration (the buckling mode).

#include "sim/solver/boundary_conditions.hpp"
#include "sim/solver/direct_cholesky.hpp"
#include "sim/solver/hyperelastic_body.hpp"

#include <Eigen/Core>

#include <memory>
#include <string>

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

/// The unprojected tangent K(x) of the free DOFs, factorised as L D L^T by a DirectCholesky: its
/// own, or one shared with the Newton solver (no second matrix and factor in memory, and a
/// factor the solver just made of the same K(x) is used as it is).
class TangentInertia {
public:
  /// With its own matrix and factor, made on first use.
  TangentInertia(const HyperelasticBody& body, const DofPartition& dofs);
  /// With `shared` (not owned; null: its own): factorize() replaces the shared matrix and factor.
  TangentInertia(const HyperelasticBody& body, const DofPartition& dofs, DirectCholesky* shared);
  ~TangentInertia();
  TangentInertia(const TangentInertia&) = delete;
  TangentInertia& operator=(const TangentInertia&) = delete;

  /// Assembles and factorises the unprojected K(x); false when a pivot is zero or not finite.
  bool factorize(const Eigen::VectorXd& x);
  /// Factorisations made so far (a factor the shared solver already held is not one).
  int factorizations() const { return m_factorizations; }
  /// Negative eigenvalues of the last factorised K.
  int negative_eigenvalues() const;
  /// Solves K y = b with the last factor (free-DOF vectors; empty without a factor).
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  /// Inverse iteration from a fixed start: the eigenpair of the last K nearest zero.
  /// `load` (free-DOF external force at full load) classifies the mode. Without a factor, only
  /// negative_eigenvalues = -1.
  StabilityMode lowest_mode(const Eigen::VectorXd& load) const;

private:
  const HyperelasticBody& m_body;
  const DofPartition& m_dofs;
  std::unique_ptr<DirectCholesky> m_own;
  DirectCholesky* m_direct = nullptr; ///< the shared one or m_own
  bool m_ok = false;
  int m_factorizations = 0;
};

} // namespace ligsim::sim
