#include "sim/solver/filtered_pcg.hpp"

#include "sim/solver/hyperelastic_body.hpp"
#include "sim/solver/parallel.hpp"

#include <Eigen/Cholesky>

#include <cmath>

namespace ligsim::sim {

FilteredPcg::FilteredPcg(const HyperelasticBody& body, const DofPartition& dofs,
                         const PcgSettings& settings)
    : m_T(body.elements())
    , m_dofs(dofs)
    , m_settings(settings)
    , m_hessians(static_cast<std::size_t>(body.element_count()) * 9 *
                 static_cast<std::size_t>(body.nodes_per_element() * body.nodes_per_element()))
    , m_block_inverse(static_cast<std::size_t>(body.node_count()))
{
}

int FilteredPcg::prepare(const HyperelasticBody& body, const Eigen::VectorXd& x, bool project,
                         double scale, const Eigen::VectorXd& mass_full,
                         const std::vector<NodeBlock>& node_blocks)
{
  const int projected =
      body.element_hessians(x, 0, body.element_count(), project, m_hessians.data());
  m_scale = scale;
  m_mass = mass_full;
  m_node_blocks = node_blocks;

  // Block-Jacobi: the 3 x 3 diagonal node blocks, with prescribed rows and columns replaced by
  // the identity so that the filtered operator stays invertible.
  std::vector<Eigen::Matrix3d> blocks(m_block_inverse.size(), Eigen::Matrix3d::Zero());
  const Eigen::Index size = 3 * m_T.cols();
  for (Eigen::Index e = 0; e < m_T.rows(); ++e) {
    const Eigen::Map<const Eigen::MatrixXd> H(m_hessians.data() + e * size * size, size, size);
    for (Eigen::Index i = 0; i < m_T.cols(); ++i)
      blocks[static_cast<std::size_t>(m_T(e, i))] += scale * H.block<3, 3>(3 * i, 3 * i);
  }
  for (const NodeBlock& block : m_node_blocks)
    blocks[static_cast<std::size_t>(block.node)] += scale * block.block;
  const Eigen::VectorXd& mask = m_dofs.free_mask();
  for (std::size_t n = 0; n < blocks.size(); ++n) {
    Eigen::Matrix3d& block = blocks[n];
    for (int a = 0; a < 3; ++a) {
      const Eigen::Index dof = 3 * static_cast<Eigen::Index>(n) + a;
      if (m_mass.size() > 0)
        block(a, a) += m_mass(dof);
      if (mask(dof) == 0.0) {
        block.row(a).setZero();
        block.col(a).setZero();
        block(a, a) = 1.0;
      }
    }
    Eigen::LLT<Eigen::Matrix3d> llt(block);
    if (llt.info() == Eigen::Success)
      m_block_inverse[n] = llt.solve(Eigen::Matrix3d::Identity());
    else // an indefinite block: fall back to the inverse absolute diagonal
      m_block_inverse[n] = block.diagonal().cwiseAbs().cwiseMax(1e-300).cwiseInverse().asDiagonal();
  }
  return projected;
}

template <int N> void FilteredPcg::apply_elements(const Eigen::VectorXd& x) const
{
  using Vector = Eigen::Matrix<double, 3 * N, 1>;
  using Matrix = Eigen::Matrix<double, 3 * N, 3 * N>;
  m_partial.resize(static_cast<std::size_t>(worker_count()));
  parallel_slices(m_T.rows(), [&](std::ptrdiff_t begin, std::ptrdiff_t end, int worker) {
    Eigen::VectorXd& local = m_partial[static_cast<std::size_t>(worker)];
    local.setZero(x.size());
    for (std::ptrdiff_t e = begin; e < end; ++e) {
      Vector xe;
      for (int i = 0; i < N; ++i)
        xe.template segment<3>(3 * i) = x.segment<3>(3 * m_T(e, i));
      const Vector ye = Eigen::Map<const Matrix>(m_hessians.data() + e * 9 * N * N) * xe;
      for (int i = 0; i < N; ++i)
        local.segment<3>(3 * m_T(e, i)) += ye.template segment<3>(3 * i);
    }
  });
}

void FilteredPcg::apply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const
{
  if (m_T.cols() == 10)
    apply_elements<10>(x);
  else
    apply_elements<4>(x);
  y.setZero(x.size());
  for (const Eigen::VectorXd& local : m_partial)
    if (local.size() == x.size())
      y += local;
  for (const NodeBlock& block : m_node_blocks)
    y.segment<3>(3 * block.node) += block.block * x.segment<3>(3 * block.node);
  y *= m_scale;
  if (m_mass.size() > 0)
    y += m_mass.cwiseProduct(x);
  y = y.cwiseProduct(m_dofs.free_mask());
}

LinearSolveReport FilteredPcg::solve(const Eigen::VectorXd& b_full, Eigen::VectorXd& y) const
{
  const Eigen::VectorXd& mask = m_dofs.free_mask();
  LinearSolveReport report;
  auto precondition = [&](const Eigen::VectorXd& r, Eigen::VectorXd& z) {
    z.resize(r.size());
    for (std::size_t n = 0; n < m_block_inverse.size(); ++n)
      z.segment<3>(3 * static_cast<Eigen::Index>(n)) =
          m_block_inverse[n] * r.segment<3>(3 * static_cast<Eigen::Index>(n));
    z = z.cwiseProduct(mask);
  };
  y = y.cwiseProduct(mask);
  const Eigen::VectorXd b = b_full.cwiseProduct(mask);
  const double b_norm = b.norm();
  if (b_norm == 0.0) {
    y.setZero();
    return report;
  }
  Eigen::VectorXd Ay;
  apply(y, Ay);
  Eigen::VectorXd r = b - Ay;
  Eigen::VectorXd z;
  precondition(r, z);
  Eigen::VectorXd p = z;
  double rz = r.dot(z);
  Eigen::VectorXd Ap;
  for (int k = 0; k < m_settings.max_iterations; ++k) {
    report.relative_residual = r.norm() / b_norm;
    if (report.relative_residual <= m_settings.tolerance) {
      report.iterations = k;
      return report;
    }
    apply(p, Ap);
    const double curvature = p.dot(Ap);
    if (!(curvature > 0.0)) {
      report.ok = false;
      report.indefinite = true;
      report.iterations = k;
      return report;
    }
    const double alpha = rz / curvature;
    y += alpha * p;
    r -= alpha * Ap;
    precondition(r, z);
    const double rz_next = r.dot(z);
    p = z + (rz_next / rz) * p;
    rz = rz_next;
  }
  report.iterations = m_settings.max_iterations;
  report.relative_residual = r.norm() / b_norm;
  report.ok = report.relative_residual <= m_settings.tolerance;
  return report;
}

} // namespace ligsim::sim
