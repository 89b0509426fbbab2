#pragma once
/// @brief A test extra potential with no energy whose "exact" Hessian block is indefinite
/// (-stiffness I on one node) and whose projection is zero: a solver that asks for the projected
/// blocks must get the body's own matrix, with none of the exact blocks left in it.

#include "sim/solver/extra_potential.hpp"

namespace ligsim::sim::test {

class IndefiniteUntilProjected final : public ExtraPotential {
public:
  IndefiniteUntilProjected(int node, double stiffness)
      : m_node(node)
      , m_stiffness(stiffness)
  {
  }
  double energy(const Eigen::VectorXd&, double, Eigen::VectorXd*) const override { return 0.0; }
  void hessian_blocks(const Eigen::VectorXd&, double, bool projected,
                      std::vector<NodeBlock>& blocks) const override
  {
    NodeBlock block;
    block.node = m_node;
    block.block = projected ? Eigen::Matrix3d::Zero()
                            : Eigen::Matrix3d(-m_stiffness * Eigen::Matrix3d::Identity());
    blocks.push_back(block);
  }
  double max_step(const Eigen::VectorXd&, const Eigen::VectorXd&, double) const override
  {
    return 1.0;
  }
  int make_admissible(Eigen::VectorXd&, double) const override { return 0; }

private:
  int m_node;
  double m_stiffness;
};

} // namespace ligsim::sim::test
