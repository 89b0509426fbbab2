#pragma once
/// @brief Constraints and loads of a quasi-static or dynamic solve, as functions of the load
/// factor t in [0, 1]: fixed and prescribed components, rigidly moved node sets, nodal forces.

#include "common/mesh.hpp"

#include <Eigen/Core>

#include <Eigen/Geometry>

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace ligsim::sim {

/// A rigid body's pose as any function of the load factor (a knee's six-degree-of-freedom path,
/// for example): the transform from the body's rest pose at t, mm.
class RigidPath {
public:
  virtual ~RigidPath() = default;
  virtual Eigen::Isometry3d pose(double t) const = 0;
};

/// A rigid motion of the load factor t: by default rotation by t * angle about the axis through
/// `point_mm`, then translation by t * translation_mm; when `path` is set, its pose at t instead
/// (the four fields are then not used).
struct RigidMotion {
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ(); ///< unit vector
  Eigen::Vector3d point_mm = Eigen::Vector3d::Zero();
  double angle_rad = 0.0;
  Eigen::Vector3d translation_mm = Eigen::Vector3d::Zero();
  std::shared_ptr<const RigidPath> path;

  /// The transform from the rest pose at load factor t.
  Eigen::Isometry3d pose(double t) const;
  Eigen::Vector3d apply(const Eigen::Vector3d& rest_mm, double t) const
  {
    return pose(t) * rest_mm;
  }
};

/// One named node set whose components are prescribed.
struct ConstraintSet {
  std::string name;
  std::vector<int> nodes;
  /// Which of x, y, z are prescribed (all three for a rigid motion).
  std::array<bool, 3> components = {true, true, true};
  /// Displacement of the prescribed components at t = 1 (zero: fixed), mm.
  Eigen::Vector3d displacement_mm = Eigen::Vector3d::Zero();
  std::optional<RigidMotion> rigid;

  /// Target position of a node with rest position `rest_mm` at load factor t (only the
  /// prescribed components are meaningful).
  Eigen::Vector3d target(const Eigen::Vector3d& rest_mm, double t) const;
};

/// The same force on every node of a set, ramped with the load factor, N.
struct NodalLoad {
  std::string name;
  std::vector<int> nodes;
  Eigen::Vector3d force_per_node_n = Eigen::Vector3d::Zero();
};

struct BoundaryConditions {
  std::vector<ConstraintSet> constraints;
  std::vector<NodalLoad> loads;
};

/// The degrees of freedom (3 per node, node-major) split into free and prescribed ones.
class DofPartition {
public:
  /// Validates node indices and that no component is prescribed twice (InputError naming the
  /// sets). Nodes flagged in `held_fixed` (for example nodes that no element uses) are held at
  /// their position as well.
  DofPartition(int node_count, const BoundaryConditions& conditions,
               const std::vector<bool>& held_fixed);

  int dof_count() const { return static_cast<int>(m_free_index.size()); }
  int free_count() const { return static_cast<int>(m_free_dofs.size()); }
  /// Index among the free DOFs, or -1 for a prescribed one.
  int free_index(int dof) const { return m_free_index[static_cast<std::size_t>(dof)]; }
  bool is_free(int dof) const { return m_free_index[static_cast<std::size_t>(dof)] >= 0; }
  const std::vector<int>& free_dofs() const { return m_free_dofs; }
  /// The free components of `full` (#DOF), in the free numbering.
  Eigen::VectorXd gather(const Eigen::VectorXd& full) const;
  /// full(free) = part, where `part` is in the free numbering; prescribed components untouched.
  void scatter(const Eigen::VectorXd& part, Eigen::VectorXd& full) const;
  /// full(free) += scale part.
  void scatter_add(const Eigen::VectorXd& part, double scale, Eigen::VectorXd& full) const;
  /// A full vector (#DOF) with `part` at the free components and zero elsewhere.
  Eigen::VectorXd expand(const Eigen::VectorXd& part) const;
  /// 1 for free DOFs, 0 for prescribed ones (the filter of filtered CG).
  const Eigen::VectorXd& free_mask() const { return m_free_mask; }

  /// Sets the prescribed components of `x` (flat positions, mm) to their targets at load factor t.
  void apply_targets(const BoundaryConditions& conditions, const Points& rest, double t,
                     Eigen::VectorXd& x) const;
  /// External nodal forces at t = 1, flat, N.
  Eigen::VectorXd external_forces(const BoundaryConditions& conditions) const;
  /// Whether any prescribed component moves with t.
  bool has_moving_targets() const { return m_moving; }

private:
  std::vector<int> m_free_index;
  std::vector<int> m_free_dofs;
  Eigen::VectorXd m_free_mask;
  bool m_moving = false;
};

/// Reaction force on each constraint set: the sum over its prescribed components of
/// `residual` = dE/dx - f_ext (the force the support exerts on the body), N.
std::vector<Eigen::Vector3d> reaction_forces(const BoundaryConditions& conditions,
                                             const Eigen::VectorXd& residual);

/// Moment of a set's reactions about `point_mm` (useful for rigid motions), N mm.
Eigen::Vector3d reaction_moment(const ConstraintSet& set, const Eigen::VectorXd& residual,
                                const Eigen::VectorXd& x, const Eigen::Vector3d& point_mm);

} // namespace ligsim::sim
