#pragma once
/// @brief Conjugate gradient on full-length DOF vectors with prescribed DOFs filtered out
/// (Baraff and Witkin's modified CG), block-Jacobi (3 x 3 per node) preconditioned, with the
/// operator applied element by element from stored element matrices.

#include "sim/material/weiss_material.hpp"
#include "sim/solver/extra_potential.hpp"
#include "sim/solver/linear_solver.hpp"

#include <Eigen/Core>

#include <vector>

namespace ligsim::sim {

class FilteredPcg {
public:
  FilteredPcg(const HyperelasticBody& body, const DofPartition& dofs, const PcgSettings& settings);

  /// Stores the element matrices of diag(mass) + scale (K(x) + node blocks) and the
  /// preconditioner.
  int prepare(const HyperelasticBody& body, const Eigen::VectorXd& x, bool project, double scale,
              const Eigen::VectorXd& mass_full, const std::vector<NodeBlock>& blocks);

  /// Solves the filtered system S A S y = S b on full-length vectors; y's prescribed entries
  /// stay zero.
  LinearSolveReport solve(const Eigen::VectorXd& b_full, Eigen::VectorXd& y_full) const;

  /// y = S A S x on full-length vectors.
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const { apply(x, y); }

  std::size_t stored_values() const { return m_hessians.size(); }

private:
  /// y = S (diag(mass) + scale (K + node blocks)) S x.
  void apply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  /// The elements' part of K x, summed per worker into m_partial.
  template <int N> void apply_elements(const Eigen::VectorXd& x) const;

  const ElementNodes& m_T;
  const DofPartition& m_dofs;
  PcgSettings m_settings;
  std::vector<double> m_hessians; ///< (3 N)^2 per element, N nodes per element
  double m_scale = 1.0;
  Eigen::VectorXd m_mass; ///< full length, may be empty
  std::vector<NodeBlock> m_node_blocks;
  std::vector<Eigen::Matrix3d> m_block_inverse;   ///< one per node
  mutable std::vector<Eigen::VectorXd> m_partial; ///< per-worker products in apply()
};

} // namespace ligsim::sim
