#pragma once
/// @brief The global stiffness of the free DOFs as a sparse lower triangle (CSC), with its
/// pattern built once and element blocks scattered straight into the value array.

#include "common/mesh.hpp"
#include "sim/material/weiss_material.hpp"
#include "sim/solver/boundary_conditions.hpp"
#include "sim/solver/hyperelastic_body.hpp"

#include <Eigen/SparseCore>

#include <array>
#include <vector>

namespace ligsim::sim {

class StiffnessMatrix {
public:
  /// The pattern of elements with the given nodes (#elements x nodes per element).
  StiffnessMatrix(const ElementNodes& elements, const DofPartition& dofs);

  /// Lower triangle (with the diagonal) of the free-DOF matrix, compressed column storage.
  const Eigen::SparseMatrix<double>& matrix() const { return m_matrix; }
  Eigen::Index nonzeros() const { return m_matrix.nonZeros(); }

  void set_zero();
  /// Adds scale * K(x) of `body` (the mesh this matrix was made for), each element's stiffness
  /// projected to positive semi-definite when `project`; returns how many needed the
  /// projection. `x` must have no inverted element. The elements are split over the workers,
  /// each scattering into its own copy of the values; the copies are summed in worker order.
  /// With `energy` and `gradient` (either may be null), the same pass gives the body's energy
  /// and gradient as HyperelasticBody::energy_gradient(); an inverted element is then reported
  /// there (and adds nothing), instead of being a precondition.
  int add_elements(const HyperelasticBody& body, const Eigen::VectorXd& x, bool project,
                   double scale = 1.0, BodyEnergy* energy = nullptr,
                   Eigen::VectorXd* gradient = nullptr);
  /// Adds scale * B (3 x 3) to the free entries of node n's own diagonal block.
  void add_node_block(int node, const Eigen::Matrix3d& B, double scale = 1.0);
  /// Adds `diagonal` (one value per free DOF) to the diagonal.
  void add_diagonal(const Eigen::VectorXd& diagonal);
  /// y = A x for the symmetric matrix (both triangles), free DOFs.
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;

private:
  /// Adds scale * H_e of element e (node-major, 3 nodes per element square) into `values`
  /// (laid out as the matrix's), at its free-DOF entries.
  template <class Matrix>
  void scatter(Eigen::Index e, const Matrix& H, double scale, double* values) const;

  /// Local pairs (p <= q) of an element's block, column by column (q outer), the order of
  /// m_scatter's entries: 78 for a linear tet, 465 for a quadratic one.
  int m_pair_count = 0;
  Eigen::SparseMatrix<double> m_matrix;
  std::vector<int> m_scatter;   ///< m_pair_count value positions per element, -1: prescribed
  std::vector<int> m_diagonal;  ///< value position of each column's diagonal
  std::vector<int> m_node_free; ///< free index of each DOF (-1: prescribed), node-major
  std::vector<std::vector<double>> m_worker_values; ///< values of workers 1, 2, ... in add_elements
};

} // namespace ligsim::sim
