#include "sim/solver/boundary_conditions.hpp"

#include "common/error.hpp"

namespace ligsim::sim {

Eigen::Isometry3d RigidMotion::pose(double t) const
{
  if (path)
    return path->pose(t);
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  transform.linear() = Eigen::AngleAxisd(t * angle_rad, axis).toRotationMatrix();
  transform.translation() = point_mm - transform.linear() * point_mm + t * translation_mm;
  return transform;
}

Eigen::Vector3d ConstraintSet::target(const Eigen::Vector3d& rest_mm, double t) const
{
  if (rigid)
    return rigid->apply(rest_mm, t);
  return rest_mm + t * displacement_mm;
}

DofPartition::DofPartition(int node_count, const BoundaryConditions& conditions,
                           const std::vector<bool>& held_fixed)
{
  const std::size_t dofs = 3 * static_cast<std::size_t>(node_count);
  std::vector<int> owner(dofs, -1); // constraint set prescribing the DOF, -2: held fixed
  for (std::size_t s = 0; s < conditions.constraints.size(); ++s) {
    const ConstraintSet& set = conditions.constraints[s];
    if (set.nodes.empty())
      fail("constraint on node set '{}': the set selects no nodes", set.name);
    if (set.rigid && !set.rigid->path && set.rigid->axis.norm() < 1e-12)
      fail("rigid motion of node set '{}': the rotation axis has zero length", set.name);
    if (set.rigid || set.displacement_mm.norm() > 0.0)
      m_moving = true;
    for (int node : set.nodes) {
      if (node < 0 || node >= node_count)
        fail("node set '{}' refers to node {}, but the mesh has {} nodes", set.name, node,
             node_count);
      for (int a = 0; a < 3; ++a) {
        if (!set.components[static_cast<std::size_t>(a)] && !set.rigid)
          continue;
        int& slot = owner[3 * static_cast<std::size_t>(node) + static_cast<std::size_t>(a)];
        if (slot >= 0 && slot != static_cast<int>(s))
          fail("node {} component {} is prescribed by both '{}' and '{}'", node, "xyz"[a],
               conditions.constraints[static_cast<std::size_t>(slot)].name, set.name);
        slot = static_cast<int>(s);
      }
    }
  }
  for (const NodalLoad& load : conditions.loads) {
    if (load.nodes.empty())
      fail("load on node set '{}': the set selects no nodes", load.name);
    for (int node : load.nodes)
      if (node < 0 || node >= node_count)
        fail("node set '{}' refers to node {}, but the mesh has {} nodes", load.name, node,
             node_count);
    if (!load.force_per_node_n.allFinite())
      fail("load on node set '{}' is not finite", load.name);
  }
  for (std::size_t n = 0; n < held_fixed.size(); ++n)
    if (held_fixed[n])
      for (std::size_t a = 0; a < 3; ++a)
        if (owner[3 * n + a] == -1)
          owner[3 * n + a] = -2;

  m_free_index.assign(dofs, -1);
  for (std::size_t dof = 0; dof < dofs; ++dof)
    if (owner[dof] == -1) {
      m_free_index[dof] = static_cast<int>(m_free_dofs.size());
      m_free_dofs.push_back(static_cast<int>(dof));
    }
  m_free_mask = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(dofs));
  for (int dof : m_free_dofs)
    m_free_mask(dof) = 1.0;
}

void DofPartition::apply_targets(const BoundaryConditions& conditions, const Points& rest, double t,
                                 Eigen::VectorXd& x) const
{
  for (const ConstraintSet& set : conditions.constraints) {
    if (set.rigid) { // one pose per set, not per node: a path may be costly to evaluate
      const Eigen::Isometry3d pose = set.rigid->pose(t);
      for (int node : set.nodes)
        x.segment<3>(3 * node) = pose * Eigen::Vector3d(rest.row(node).transpose());
      continue;
    }
    for (int node : set.nodes) {
      const Eigen::Vector3d target = set.target(rest.row(node).transpose(), t);
      for (int a = 0; a < 3; ++a)
        if (set.components[static_cast<std::size_t>(a)])
          x(3 * node + a) = target(a);
    }
  }
}

Eigen::VectorXd DofPartition::external_forces(const BoundaryConditions& conditions) const
{
  Eigen::VectorXd forces = Eigen::VectorXd::Zero(dof_count());
  for (const NodalLoad& load : conditions.loads)
    for (int node : load.nodes)
      forces.segment<3>(3 * node) += load.force_per_node_n;
  return forces;
}

std::vector<Eigen::Vector3d> reaction_forces(const BoundaryConditions& conditions,
                                             const Eigen::VectorXd& residual)
{
  std::vector<Eigen::Vector3d> reactions;
  for (const ConstraintSet& set : conditions.constraints) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int node : set.nodes)
      for (int a = 0; a < 3; ++a)
        if (set.rigid || set.components[static_cast<std::size_t>(a)])
          sum(a) += residual(3 * node + a);
    reactions.push_back(sum);
  }
  return reactions;
}

Eigen::Vector3d reaction_moment(const ConstraintSet& set, const Eigen::VectorXd& residual,
                                const Eigen::VectorXd& x, const Eigen::Vector3d& point_mm)
{
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  for (int node : set.nodes) {
    Eigen::Vector3d force = Eigen::Vector3d::Zero();
    for (int a = 0; a < 3; ++a)
      if (set.rigid || set.components[static_cast<std::size_t>(a)])
        force(a) = residual(3 * node + a);
    moment += (x.segment<3>(3 * node) - point_mm).cross(force);
  }
  return moment;
}

Eigen::VectorXd DofPartition::gather(const Eigen::VectorXd& full) const
{
  Eigen::VectorXd part(free_count());
  for (std::size_t f = 0; f < m_free_dofs.size(); ++f)
    part(static_cast<Eigen::Index>(f)) = full(m_free_dofs[f]);
  return part;
}

void DofPartition::scatter(const Eigen::VectorXd& part, Eigen::VectorXd& full) const
{
  for (std::size_t f = 0; f < m_free_dofs.size(); ++f)
    full(m_free_dofs[f]) = part(static_cast<Eigen::Index>(f));
}

void DofPartition::scatter_add(const Eigen::VectorXd& part, double scale,
                               Eigen::VectorXd& full) const
{
  for (std::size_t f = 0; f < m_free_dofs.size(); ++f)
    full(m_free_dofs[f]) += scale * part(static_cast<Eigen::Index>(f));
}

Eigen::VectorXd DofPartition::expand(const Eigen::VectorXd& part) const
{
  Eigen::VectorXd full = Eigen::VectorXd::Zero(dof_count());
  scatter(part, full);
  return full;
}

} // namespace ligsim::sim
