#pragma once
/// @brief An energy term beside the body's strain energy (contact with rigid obstacles) that the
/// Newton and implicit Euler solvers add when one is given: energy, gradient, 3 x 3 Hessian
/// blocks on single nodes (they fit the stiffness pattern) and a bound on the step length.

#include <Eigen/Core>

#include <vector>

namespace ligsim::sim {

/// d^2E/dx_n^2 of one node, N/mm.
struct NodeBlock {
  int node = 0;
  Eigen::Matrix3d block = Eigen::Matrix3d::Zero();
};

/// A potential that depends on node positions and on the load factor t (its obstacles may move
/// with t). It acts on free nodes only. Energy +infinity marks an inadmissible state.
class ExtraPotential {
public:
  virtual ~ExtraPotential() = default;

  /// Energy at positions x (flat, mm) and load factor t, N mm; adds dE/dx into `gradient` when
  /// it is not null (a vector of the full DOF length).
  virtual double energy(const Eigen::VectorXd& x, double t, Eigen::VectorXd* gradient) const = 0;

  /// Appends the Hessian blocks at (x, t) to `blocks`: each projected to positive semi-definite
  /// (`projected`), or the exact ones (which may be indefinite; where the whole matrix stays
  /// definite with them, Newton converges quadratically).
  virtual void hessian_blocks(const Eigen::VectorXd& x, double t, bool projected,
                              std::vector<NodeBlock>& blocks) const = 0;

  /// The largest fraction in [0, 1] of the move x -> x + dx (t fixed) along which the state stays
  /// admissible (no node crosses an obstacle's surface).
  virtual double max_step(const Eigen::VectorXd& x, const Eigen::VectorXd& dx, double t) const = 0;

  /// Makes x admissible at t after the obstacles moved (for example by moving free nodes out of
  /// an obstacle that moved over them); returns how many nodes it moved.
  virtual int make_admissible(Eigen::VectorXd& x, double t) const = 0;
};

} // namespace ligsim::sim
