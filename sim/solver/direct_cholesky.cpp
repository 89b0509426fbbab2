#include "sim/solver/direct_cholesky.hpp"

#include "sim/solver/hyperelastic_body.hpp"

#include <algorithm>

namespace ligsim::sim {

namespace {

/// Elements whose stiffness is computed (in parallel) before being scattered (serially).
constexpr Eigen::Index chunk_size = 4096;
/// Lagged-factor CG: give up (and refactorise) beyond this many iterations; refactorise before
/// the next solve when one needed more than `slow_iterations`.
constexpr int lagged_iteration_limit = 40;
constexpr int slow_iterations = 20;
/// Relative residual of lagged-factor CG solves.
constexpr double lagged_tolerance = 1e-8;

} // namespace

DirectCholesky::DirectCholesky(const HyperelasticBody& body, const DofPartition& dofs)
    : m_stiffness(body.mesh().T, dofs)
    , m_chunk(static_cast<std::size_t>(std::min<Eigen::Index>(chunk_size, body.element_count())))
{
  m_cholesky.cholmod().print = 0; // indefinite matrices are reported through info()
  // Nested dissection (METIS) gives less fill than AMD on 3-D meshes.
  m_cholesky.cholmod().nmethods = 1;
  m_cholesky.cholmod().method[0].ordering = CHOLMOD_METIS;
}

int DirectCholesky::prepare(const HyperelasticBody& body, const Eigen::VectorXd& x, bool project,
                            double scale, const Eigen::VectorXd& mass,
                            const std::vector<NodeBlock>& blocks)
{
  m_stiffness.set_zero();
  int projected = 0;
  const Eigen::Index count = body.element_count();
  for (Eigen::Index begin = 0; begin < count; begin += chunk_size) {
    const Eigen::Index end = std::min(count, begin + chunk_size);
    projected += body.element_hessians(x, begin, end, project, m_chunk.data());
    for (Eigen::Index e = begin; e < end; ++e)
      m_stiffness.add_element(e, m_chunk[static_cast<std::size_t>(e - begin)], scale);
  }
  for (const NodeBlock& block : blocks)
    m_stiffness.add_node_block(block.node, block.block, scale);
  if (mass.size() > 0)
    m_stiffness.add_diagonal(mass);
  m_factor_fresh = false;
  return projected;
}

bool DirectCholesky::factorize()
{
  if (!m_analyzed) {
    m_cholesky.analyzePattern(m_stiffness.matrix());
    m_analyzed = true;
  }
  m_cholesky.factorize(m_stiffness.matrix());
  ++m_factorizations;
  m_has_factor = m_cholesky.info() == Eigen::Success;
  m_factor_fresh = m_has_factor;
  m_refactor_next = false;
  return m_has_factor;
}

bool DirectCholesky::lagged_cg(const Eigen::VectorXd& b, Eigen::VectorXd& y, int limit,
                               LinearSolveReport& report)
{
  const double b_norm = b.norm();
  y = m_cholesky.solve(b);
  Eigen::VectorXd Ay;
  m_stiffness.multiply(y, Ay);
  Eigen::VectorXd r = b - Ay;
  Eigen::VectorXd z = m_cholesky.solve(r);
  Eigen::VectorXd p = z;
  double rz = r.dot(z);
  Eigen::VectorXd Ap;
  for (int k = 1;; ++k) {
    report.relative_residual = r.norm() / b_norm;
    if (report.relative_residual <= lagged_tolerance) {
      report.iterations += k;
      m_refactor_next = k > slow_iterations;
      return true;
    }
    if (k > limit)
      break;
    m_stiffness.multiply(p, Ap);
    const double curvature = p.dot(Ap);
    if (!(curvature > 0.0))
      break;
    const double alpha = rz / curvature;
    y += alpha * p;
    r -= alpha * Ap;
    z = m_cholesky.solve(r);
    const double rz_next = r.dot(z);
    p = z + (rz_next / rz) * p;
    rz = rz_next;
  }
  report.iterations += limit;
  return false;
}

LinearSolveReport DirectCholesky::solve(const Eigen::VectorXd& b, Eigen::VectorXd& y)
{
  LinearSolveReport report;
  if (b.norm() == 0.0) {
    y = Eigen::VectorXd::Zero(b.size());
    return report;
  }
  if (m_has_factor && !m_factor_fresh && !m_refactor_next &&
      lagged_cg(b, y, lagged_iteration_limit, report))
    return report;
  ++report.factorizations;
  if (!factorize()) {
    report.ok = false;
    report.indefinite = true;
    return report;
  }
  y = m_cholesky.solve(b);
  report.ok = y.allFinite();
  return report;
}

} // namespace ligsim::sim
