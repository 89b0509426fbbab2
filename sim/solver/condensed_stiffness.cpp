#include "sim/solver/condensed_stiffness.hpp"

#include "common/error.hpp"
#include "sim/solver/linear_solver.hpp"

#include <vector>

namespace ligsim::sim {

CondensedStiffness condensed_stiffness(const HyperelasticBody& body,
                                       const BoundaryConditions& conditions,
                                       const Eigen::VectorXd& x, const ExtraPotential* extra,
                                       double t, const Eigen::MatrixXd& D,
                                       const Eigen::MatrixXd* coupling)
{
  const DofPartition dofs(body.node_count(), conditions, body.unreferenced_nodes());
  const Eigen::Index m = D.cols();
  // The prescribed part of each motion, and K d for it.
  Eigen::MatrixXd prescribed = Eigen::MatrixXd::Zero(D.rows(), m);
  for (int dof = 0; dof < dofs.dof_count(); ++dof)
    if (!dofs.is_free(dof))
      prescribed.row(dof) = D.row(dof);
  Eigen::MatrixXd KD(D.rows(), m);
  for (Eigen::Index k = 0; k < m; ++k)
    KD.col(k) = body.apply_stiffness(x, prescribed.col(k));
  Eigen::MatrixXd free_part(dofs.free_count(), m);
  for (int f = 0; f < dofs.free_count(); ++f) {
    const int dof = dofs.free_dofs()[static_cast<std::size_t>(f)];
    free_part.row(f) = KD.row(dof);
    if (coupling != nullptr)
      free_part.row(f) += coupling->row(dof);
  }

  CondensedStiffness result;
  result.matrix = prescribed.transpose() * KD;
  std::vector<NodeBlock> blocks;
  StiffnessSolver solver(body, dofs, LinearSolverKind::direct, PcgSettings{});
  for (const bool project : {false, true}) {
    blocks.clear();
    if (extra != nullptr)
      extra->hessian_blocks(x, t, project, blocks);
    solver.prepare(x, project, 1.0, Eigen::VectorXd(), blocks);
    Eigen::MatrixXd U(dofs.free_count(), m);
    bool ok = true;
    for (Eigen::Index k = 0; k < m && ok; ++k) {
      Eigen::VectorXd u = Eigen::VectorXd::Zero(dofs.free_count());
      const LinearSolveReport report = solver.solve(free_part.col(k), u);
      ok = report.ok && !report.indefinite;
      U.col(k) = u;
    }
    if (!ok)
      continue;
    if (project)
      result.factor = "projected";
    result.matrix -= free_part.transpose() * U;
    result.matrix = 0.5 * (result.matrix + result.matrix.transpose()).eval();
    result.free_response = Eigen::MatrixXd::Zero(D.rows(), m);
    for (int f = 0; f < dofs.free_count(); ++f)
      result.free_response.row(dofs.free_dofs()[static_cast<std::size_t>(f)]) = -U.row(f);
    return result;
  }
  fail<SolverError>("condensed stiffness: the free stiffness cannot be factorised, even "
                    "projected to positive semi-definite");
}

} // namespace ligsim::sim
