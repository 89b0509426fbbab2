#pragma once
/// @brief The stiffness a body shows at its prescribed degrees of freedom once its free ones have
/// come back to equilibrium: the Schur complement S = K_pp - K_pf K_ff^-1 K_fp of the tangent
/// stiffness (with an extra potential's exact Hessian in K_ff), seen along a few prescribed
/// motions. A solver that makes a rigid body's pose an unknown, with the body's nodes eliminated,
/// needs S along the pose's directions: it is the exact derivative of the support's reaction.

#include "sim/solver/boundary_conditions.hpp"
#include "sim/solver/extra_potential.hpp"
#include "sim/solver/hyperelastic_body.hpp"

#include <Eigen/Core>

#include <string>

namespace ligsim::sim {

struct CondensedStiffness {
  Eigen::MatrixXd matrix; ///< D^T S D (m x m), symmetric
  /// How K_ff was factorised: "exact", or "projected" when the exact one is not positive
  /// definite (past a buckling point): then `matrix` is that of the projected stiffness.
  std::string factor = "exact";
  /// How the free DOFs follow each motion back to equilibrium, -K_ff^-1 B (#DOF x m; zero rows at
  /// the prescribed DOFs): a first-order guess of the equilibrium after a small motion.
  Eigen::MatrixXd free_response;
};

/// D^T S D at the equilibrium x of `body` in `conditions` (the free DOFs those leave), with the
/// extra potential (may be null) at load factor t in K_ff. D: #DOF x m, each column a motion of
/// the prescribed DOFs (its free entries are ignored). `coupling` (#DOF x m, its free rows used;
/// may be null) adds to K_fp D what else the motions pull the free DOFs with (a moving obstacle's
/// mixed derivatives): the result is then D^T K_pp D - B^T K_ff^-1 B with B = K_fp D + coupling.
/// Throws SolverError when K_ff cannot be factorised even projected.
CondensedStiffness condensed_stiffness(const HyperelasticBody& body,
                                       const BoundaryConditions& conditions,
                                       const Eigen::VectorXd& x, const ExtraPotential* extra,
                                       double t, const Eigen::MatrixXd& D,
                                       const Eigen::MatrixXd* coupling = nullptr);

} // namespace ligsim::sim
