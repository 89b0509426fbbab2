#include "sim/solver/linear_solver.hpp"

#include "common/error.hpp"
#include "sim/solver/direct_cholesky.hpp"
#include "sim/solver/filtered_pcg.hpp"

#include <cmath>

namespace ligsim::sim {

LinearSolverKind parse_linear_solver(const std::string& text, const std::string& where)
{
  if (text == "direct")
    return LinearSolverKind::direct;
  if (text == "pcg")
    return LinearSolverKind::pcg;
  fail("{}: linear solver must be \"direct\" or \"pcg\", got \"{}\"", where, text);
}

std::string to_string(LinearSolverKind kind)
{
  return kind == LinearSolverKind::direct ? "direct" : "pcg";
}

StiffnessSolver::StiffnessSolver(const HyperelasticBody& body, const DofPartition& dofs,
                                 LinearSolverKind kind, const PcgSettings& pcg)
    : m_body(body)
    , m_dofs(dofs)
    , m_kind(kind)
{
  if (kind == LinearSolverKind::direct)
    m_direct = std::make_unique<DirectCholesky>(body, dofs);
  else
    m_pcg = std::make_unique<FilteredPcg>(body, dofs, pcg);
}

StiffnessSolver::~StiffnessSolver() = default;

int StiffnessSolver::prepare(const Eigen::VectorXd& x, bool project, double stiffness_scale,
                             const Eigen::VectorXd& mass, const std::vector<NodeBlock>& blocks,
                             BodyEnergy* energy, Eigen::VectorXd* gradient)
{
  if (m_direct)
    return m_direct->prepare(m_body, x, project, stiffness_scale, mass, blocks, energy, gradient);
  if (energy) {
    Eigen::VectorXd own;
    *energy = m_body.energy_gradient(x, gradient ? *gradient : own);
    if (!std::isfinite(energy->energy))
      return 0;
  }
  const Eigen::VectorXd mass_full = mass.size() > 0 ? m_dofs.expand(mass) : Eigen::VectorXd();
  return m_pcg->prepare(m_body, x, project, stiffness_scale, mass_full, blocks);
}

LinearSolveReport StiffnessSolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& y)
{
  if (m_direct)
    return m_direct->solve(b, y);
  const Eigen::VectorXd b_full = m_dofs.expand(b);
  Eigen::VectorXd y_full =
      y.size() == b.size() ? m_dofs.expand(y) : Eigen::VectorXd::Zero(m_dofs.dof_count());
  const LinearSolveReport report = m_pcg->solve(b_full, y_full);
  y = m_dofs.gather(y_full);
  return report;
}

void StiffnessSolver::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const
{
  if (m_direct) {
    m_direct->multiply(x, y);
    return;
  }
  Eigen::VectorXd y_full;
  m_pcg->multiply(m_dofs.expand(x), y_full);
  y = m_dofs.gather(y_full);
}

std::size_t StiffnessSolver::stored_values() const
{
  return m_direct ? m_direct->stored_values() : m_pcg->stored_values();
}

} // namespace ligsim::sim
