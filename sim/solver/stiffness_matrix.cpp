#include "sim/solver/stiffness_matrix.hpp"

#include "sim/solver/parallel.hpp"

#include <algorithm>

namespace ligsim::sim {

StiffnessMatrix::StiffnessMatrix(const ElementNodes& T, const DofPartition& dofs)
{
  const int node_count = dofs.dof_count() / 3;
  const int nodes = static_cast<int>(T.cols());
  std::vector<std::vector<int>> neighbours(static_cast<std::size_t>(node_count));
  for (Eigen::Index e = 0; e < T.rows(); ++e)
    for (int i = 0; i < nodes; ++i)
      for (int j = 0; j < nodes; ++j)
        neighbours[static_cast<std::size_t>(T(e, i))].push_back(T(e, j));
  for (auto& list : neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }

  // Column c (free DOF 3n + a) holds the free DOFs 3m + b >= 3n + a of n's neighbours m. The
  // free numbering follows the global one, so rows come out sorted.
  const int n_free = dofs.free_count();
  std::vector<int> outer(static_cast<std::size_t>(n_free) + 1, 0);
  std::vector<int> inner;
  for (int column = 0; column < n_free; ++column) {
    const int dof = dofs.free_dofs()[static_cast<std::size_t>(column)];
    const int node = dof / 3;
    for (int m : neighbours[static_cast<std::size_t>(node)])
      for (int b = 0; b < 3; ++b) {
        const int row_dof = 3 * m + b;
        if (row_dof >= dof && dofs.is_free(row_dof))
          inner.push_back(dofs.free_index(row_dof));
      }
    outer[static_cast<std::size_t>(column) + 1] = static_cast<int>(inner.size());
  }
  m_matrix.resize(n_free, n_free);
  m_matrix.resizeNonZeros(static_cast<Eigen::Index>(inner.size()));
  std::copy(outer.begin(), outer.end(), m_matrix.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), m_matrix.innerIndexPtr());
  set_zero();

  auto position = [&](int row, int column) {
    const int* first = m_matrix.innerIndexPtr() + outer[static_cast<std::size_t>(column)];
    const int* last = m_matrix.innerIndexPtr() + outer[static_cast<std::size_t>(column) + 1];
    return static_cast<int>(std::lower_bound(first, last, row) - m_matrix.innerIndexPtr());
  };
  m_diagonal.resize(static_cast<std::size_t>(n_free));
  for (int column = 0; column < n_free; ++column)
    m_diagonal[static_cast<std::size_t>(column)] = position(column, column);

  m_node_free.resize(static_cast<std::size_t>(dofs.dof_count()));
  for (int dof = 0; dof < dofs.dof_count(); ++dof)
    m_node_free[static_cast<std::size_t>(dof)] = dofs.free_index(dof);

  m_pair_count = 3 * nodes * (3 * nodes + 1) / 2;
  const auto pairs = static_cast<std::size_t>(m_pair_count);
  m_scatter.assign(static_cast<std::size_t>(T.rows()) * pairs, -1);
  for (Eigen::Index e = 0; e < T.rows(); ++e) {
    int k = 0;
    for (int q = 0; q < 3 * nodes; ++q)
      for (int p = 0; p <= q; ++p, ++k) {
        const int fp = dofs.free_index(3 * T(e, p / 3) + p % 3);
        const int fq = dofs.free_index(3 * T(e, q / 3) + q % 3);
        if (fp >= 0 && fq >= 0)
          m_scatter[static_cast<std::size_t>(e) * pairs + static_cast<std::size_t>(k)] =
              position(std::max(fp, fq), std::min(fp, fq));
      }
  }
}

void StiffnessMatrix::set_zero()
{
  std::fill(m_matrix.valuePtr(), m_matrix.valuePtr() + m_matrix.nonZeros(), 0.0);
}

template <class Matrix>
void StiffnessMatrix::scatter(Eigen::Index e, const Matrix& H, double scale, double* values) const
{
  const int* positions =
      m_scatter.data() + static_cast<std::size_t>(e) * static_cast<std::size_t>(m_pair_count);
  int k = 0;
  for (int q = 0; q < Matrix::RowsAtCompileTime; ++q)
    for (int p = 0; p <= q; ++p, ++k)
      if (positions[k] >= 0)
        values[positions[k]] += scale * H(p, q);
}

int StiffnessMatrix::add_elements(const HyperelasticBody& body, const Eigen::VectorXd& x,
                                  bool project, double scale, BodyEnergy* energy,
                                  Eigen::VectorXd* gradient)
{
  const std::size_t workers = static_cast<std::size_t>(worker_count());
  m_worker_values.resize(workers - 1);
  std::vector<char> ran(workers, 0);
  const auto count = static_cast<std::size_t>(m_matrix.nonZeros());
  int projected = 0;
  const BodyEnergy sum = body.stiffness_pass(x, project, gradient, projected,
                                             [&](Eigen::Index e, const auto& H, int worker) {
                                               const auto w = static_cast<std::size_t>(worker);
                                               if (w == 0) {
                                                 scatter(e, H, scale, m_matrix.valuePtr());
                                                 return;
                                               }
                                               if (!ran[w]) {
                                                 ran[w] = 1;
                                                 m_worker_values[w - 1].assign(count, 0.0);
                                               }
                                               scatter(e, H, scale, m_worker_values[w - 1].data());
                                             });
  if (energy)
    *energy = sum;
  // Each entry sums the workers' parts in worker order, whatever the slicing of the entries.
  parallel_slices(static_cast<std::ptrdiff_t>(count),
                  [&](std::ptrdiff_t begin, std::ptrdiff_t end, int) {
                    double* values = m_matrix.valuePtr();
                    for (std::size_t w = 1; w < workers; ++w)
                      if (ran[w])
                        for (std::ptrdiff_t i = begin; i < end; ++i)
                          values[i] += m_worker_values[w - 1][static_cast<std::size_t>(i)];
                  });
  return projected;
}

void StiffnessMatrix::add_node_block(int node, const Eigen::Matrix3d& B, double scale)
{
  // A node's free DOFs are consecutive in the free numbering, so in the column of its DOF a the
  // rows of its later DOFs follow the diagonal directly.
  double* values = m_matrix.valuePtr();
  const int* free = m_node_free.data() + 3 * static_cast<std::size_t>(node);
  for (int a = 0; a < 3; ++a) {
    if (free[a] < 0)
      continue;
    int position = m_diagonal[static_cast<std::size_t>(free[a])];
    for (int b = a; b < 3; ++b)
      if (free[b] >= 0)
        values[position++] += scale * B(b, a);
  }
}

void StiffnessMatrix::add_diagonal(const Eigen::VectorXd& diagonal)
{
  double* values = m_matrix.valuePtr();
  for (std::size_t c = 0; c < m_diagonal.size(); ++c)
    values[m_diagonal[c]] += diagonal(static_cast<Eigen::Index>(c));
}

void StiffnessMatrix::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const
{
  y = m_matrix.selfadjointView<Eigen::Lower>() * x;
}

} // namespace ligsim::sim
