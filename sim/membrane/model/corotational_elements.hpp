#pragma once
/// @brief Co-rotational linear triangles with the transversely isotropic stiffness of eq. 1.
///
/// Per element, from the rest shape (precomputed once, and again when a split changes it):
/// the barycentric gradients g_i, the material stiffness C(theta) of the element's fiber angle
/// and the 6 x 6 element stiffness K_e = h A B^T C B. Each step the rotation R is the polar
/// rotation of the deformation gradient F = R S; the element then acts linearly in its rotated
/// frame: u_i = R^T x_i - X_i, f_i = -R (K_e u)_i, stress = C B u. (R is the rotation closest
/// to F, so an inverted element gets forces that restore it.) Stresses and fibers are thus
/// in the rest frame, where the crack directions are searched. The tangent used by the implicit
/// solve is R K_e R^T (the usual co-rotational approximation without dR/dx).

#include "sim/membrane/mesh/membrane_mesh.hpp"
#include "sim/membrane/model/material.hpp"

#include <Eigen/Core>

#include <vector>

namespace ligsim::membrane {

using ElementMatrix = Eigen::Matrix<double, 6, 6>;

class CorotationalElements {
public:
  explicit CorotationalElements(const MembraneMaterial& material)
      : m_material(material)
  {
  }

  /// (Re)computes the rest data of every triangle of `mesh`.
  void rebuild(const MembraneMesh& mesh);
  /// (Re)computes the rest data of triangle `tri` (growing the arrays if it is new). Its
  /// rotation and stress are taken from `parent` (the triangle it was split from, or itself)
  /// until the next add_forces; without a parent they start as identity and zero.
  void refresh(const MembraneMesh& mesh, int tri, int parent = -1);

  /// Internal forces at the current positions (added into `forces`, #nodes), updating each
  /// element's rotation and stress. Throws SolverError naming the element if a position is
  /// not finite.
  void add_forces(const MembraneMesh& mesh, std::vector<Vec2>& forces);

  /// out += K p with the tangent R K_e R^T of the last add_forces (p and out #nodes).
  void add_stiffness_times(const MembraneMesh& mesh, const std::vector<Vec2>& p,
                           std::vector<Vec2>& out) const;

  /// diagonal += diag(K) (#nodes, x and y entries).
  void add_stiffness_diagonal(const MembraneMesh& mesh, std::vector<Vec2>& diagonal) const;

  /// Stress of each element, (sigma_x, sigma_y, tau_xy) in the rest frame, MPa.
  const Eigen::Vector3d& stress(int tri) const { return m_stress[tri]; }
  /// Rotation of each element from the rest to the current frame (cos, sin).
  const Vec2& rotation(int tri) const { return m_rotation[tri]; }
  const MembraneMaterial& material() const { return m_material; }

private:
  MembraneMaterial m_material;
  std::vector<ElementMatrix> m_stiffness;            ///< K_e, N/mm
  std::vector<Eigen::Matrix<double, 3, 6>> m_strain; ///< B: strain from local displacements
  std::vector<Eigen::Matrix3d> m_material_stiffness; ///< C(theta), MPa
  std::vector<Vec2> m_rotation;                      ///< (cos, sin) of R
  std::vector<Eigen::Vector3d> m_stress;             ///< MPa
  std::vector<Eigen::Matrix2d> m_rest_inverse;       ///< D_m^-1, 1/mm
};

} // namespace ligsim::membrane
