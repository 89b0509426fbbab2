#include "sim/solver/direct_cholesky.hpp"

#include "sim/solver/hyperelastic_body.hpp"

#include <algorithm>
#include <cmath>

namespace ligsim::sim {

namespace {

/// Relative residual of lagged-factor CG solves.
constexpr double lagged_tolerance = 1e-8;
/// CG iterations that measure the convergence rate of a lagged solve.
constexpr int rate_iterations = 5;
/// Bounds of the lagged factor's CG budget per factorisation.
constexpr int min_iteration_budget = 4;
constexpr int max_iteration_budget = 40;

} // namespace

DirectCholesky::DirectCholesky(const HyperelasticBody& body, const DofPartition& dofs)
    : m_stiffness(body.elements(), dofs)
{
}

int DirectCholesky::prepare(const HyperelasticBody& body, const Eigen::VectorXd& x, bool project,
                            double scale, const Eigen::VectorXd& mass,
                            const std::vector<NodeBlock>& blocks, BodyEnergy* energy,
                            Eigen::VectorXd* gradient)
{
  m_stiffness.set_zero();
  const int projected = m_stiffness.add_elements(body, x, project, scale, energy, gradient);
  for (const NodeBlock& block : blocks)
    m_stiffness.add_node_block(block.node, block.block, scale);
  if (mass.size() > 0)
    m_stiffness.add_diagonal(mass);
  m_factor_fresh = false;
  m_plain_tangent = !project && scale == 1.0 && mass.size() == 0 && blocks.empty();
  if (m_plain_tangent)
    m_tangent_x = x;
  return projected;
}

bool DirectCholesky::factorize()
{
  if (!m_ldlt.analyzed()) {
    m_ldlt.analyze(m_stiffness.matrix());
    // A CG iteration reads the factor (forward and back substitution) and the matrix.
    const double iteration_cost =
        static_cast<double>(m_ldlt.factor_entries()) + static_cast<double>(m_stiffness.nonzeros());
    m_iteration_budget =
        std::clamp(static_cast<int>(std::lround(m_ldlt.factorization_cost() / iteration_cost)),
                   min_iteration_budget, max_iteration_budget);
  }
  const bool ok = m_ldlt.factorize(m_stiffness.matrix());
  ++m_factorizations;
  m_factor_fresh = ok;
  m_has_factor = ok && m_ldlt.negative_pivots() == 0;
  m_refactor_next = false;
  m_lagged_iterations = 0;
  return ok;
}

bool DirectCholesky::holds_tangent(const Eigen::VectorXd& x) const
{
  return m_factor_fresh && m_plain_tangent && x.size() == m_tangent_x.size() && x == m_tangent_x;
}

bool DirectCholesky::lagged_cg(const Eigen::VectorXd& b, Eigen::VectorXd& y,
                               LinearSolveReport& report)
{
  const double b_norm = b.norm();
  // A lagged factor only preconditions: single precision halves the traffic of its solves.
  m_ldlt.to_single_precision();
  y = m_ldlt.solve(b);
  Eigen::VectorXd Ay;
  m_stiffness.multiply(y, Ay);
  Eigen::VectorXd r = b - Ay;
  Eigen::VectorXd z = m_ldlt.solve(r);
  Eigen::VectorXd p = z;
  double rz = r.dot(z);
  Eigen::VectorXd Ap;
  double first_residual = 0.0;
  int k = 0;
  for (;; ++k) {
    report.relative_residual = r.norm() / b_norm;
    if (report.relative_residual <= lagged_tolerance) {
      report.iterations += k;
      return true;
    }
    if (k == 0)
      first_residual = report.relative_residual;
    // Give up (and factorise) once the iterations still to go, at the rate so far, would cost
    // more than a factorisation.
    if (k >= rate_iterations) {
      const double rate = std::pow(report.relative_residual / first_residual, 1.0 / k);
      if (!(rate < 1.0) || std::log(lagged_tolerance / report.relative_residual) / std::log(rate) >
                               m_iteration_budget)
        break;
    }
    if (k >= 2 * m_iteration_budget)
      break;
    m_stiffness.multiply(p, Ap);
    const double curvature = p.dot(Ap);
    if (!(curvature > 0.0))
      break;
    const double alpha = rz / curvature;
    y += alpha * p;
    r -= alpha * Ap;
    z = m_ldlt.solve(r);
    const double rz_next = r.dot(z);
    p = z + (rz_next / rz) * p;
    rz = rz_next;
  }
  report.iterations += k;
  return false;
}

LinearSolveReport DirectCholesky::solve(const Eigen::VectorXd& b, Eigen::VectorXd& y)
{
  LinearSolveReport report;
  if (b.norm() == 0.0) {
    y = Eigen::VectorXd::Zero(b.size());
    return report;
  }
  if (m_has_factor && !m_factor_fresh && !m_refactor_next) {
    if (lagged_cg(b, y, report)) {
      // Refactorise once the iterations spent on this factor would have paid for a new one.
      m_lagged_iterations += report.iterations;
      m_refactor_next = m_lagged_iterations > m_iteration_budget;
      return report;
    }
  }
  ++report.factorizations;
  if (!factorize() || m_ldlt.negative_pivots() > 0) {
    report.ok = false;
    report.indefinite = true;
    return report;
  }
  y = m_ldlt.solve(b);
  report.ok = y.allFinite();
  return report;
}

} // namespace ligsim::sim
