#include "sim/membrane/model/corotational_elements.hpp"

#include "common/error.hpp"
#include "sim/membrane/model/stiffness.hpp"

#include <Eigen/LU>

#include <cmath>

namespace ligsim::membrane {

void CorotationalElements::rebuild(const MembraneMesh& mesh)
{
  m_stiffness.clear();
  m_strain.clear();
  m_material_stiffness.clear();
  m_rotation.clear();
  m_stress.clear();
  m_rest_inverse.clear();
  for (int tri = 0; tri < mesh.triangle_count(); ++tri)
    refresh(mesh, tri);
}

void CorotationalElements::refresh(const MembraneMesh& mesh, int tri, int parent)
{
  const std::size_t n = static_cast<std::size_t>(mesh.triangle_count());
  if (m_stiffness.size() < n) {
    m_stiffness.resize(n);
    m_strain.resize(n);
    m_material_stiffness.resize(n);
    m_rotation.resize(n, Vec2(1.0, 0.0));
    m_stress.resize(n, Eigen::Vector3d::Zero());
    m_rest_inverse.resize(n);
  }
  const Triangle& t = mesh.triangles[tri];
  Eigen::Matrix2d rest_edges;
  rest_edges << mesh.rest[t[1]] - mesh.rest[t[0]], mesh.rest[t[2]] - mesh.rest[t[0]];
  const Eigen::Matrix2d inverse = rest_edges.inverse();
  m_rest_inverse[tri] = inverse;
  // Barycentric gradients: rows of D_m^-1 for nodes 1 and 2, minus their sum for node 0.
  const Vec2 g1 = inverse.row(0).transpose(), g2 = inverse.row(1).transpose();
  const Vec2 g[3] = {-g1 - g2, g1, g2};
  Eigen::Matrix<double, 3, 6> b = Eigen::Matrix<double, 3, 6>::Zero();
  for (int i = 0; i < 3; ++i) {
    b(0, 2 * i) = g[i].x();
    b(1, 2 * i + 1) = g[i].y();
    b(2, 2 * i) = g[i].y();
    b(2, 2 * i + 1) = g[i].x();
  }
  const Eigen::Matrix3d c = rotated_stiffness(m_material, mesh.fiber_angle_rad[tri]);
  const double volume = m_material.thickness_mm * rest_area(mesh, tri);
  m_strain[tri] = b;
  m_material_stiffness[tri] = c;
  m_stiffness[tri] = volume * b.transpose() * c * b;
  m_rotation[tri] = parent >= 0 ? m_rotation[parent] : Vec2(1.0, 0.0);
  m_stress[tri] = parent >= 0 ? m_stress[parent] : Eigen::Vector3d::Zero();
}

void CorotationalElements::add_forces(const MembraneMesh& mesh, std::vector<Vec2>& forces)
{
  for (int tri = 0; tri < mesh.triangle_count(); ++tri) {
    const Triangle& t = mesh.triangles[tri];
    const Vec2 &x0 = mesh.position[t[0]], &x1 = mesh.position[t[1]], &x2 = mesh.position[t[2]];
    Eigen::Matrix2d current_edges;
    current_edges << x1 - x0, x2 - x0;
    const Eigen::Matrix2d f = current_edges * m_rest_inverse[tri];
    // The rotation closest to F (the polar one where det F > 0): the angle of
    // (f00 + f11, f10 - f01). It stays a proper rotation for an inverted element, whose
    // linear forces in the rotated frame then push it back (Irving et al. 2004).
    const double cos_part = f(0, 0) + f(1, 1), sin_part = f(1, 0) - f(0, 1);
    const double norm = std::hypot(cos_part, sin_part);
    if (!std::isfinite(norm))
      fail<SolverError>("membrane element {} has a non-finite deformation", tri);
    const double c = norm > 0.0 ? cos_part / norm : m_rotation[tri].x();
    const double s = norm > 0.0 ? sin_part / norm : m_rotation[tri].y();
    m_rotation[tri] = Vec2(c, s);
    Eigen::Matrix<double, 6, 1> u;
    for (int i = 0; i < 3; ++i) {
      const Vec2& x = mesh.position[t[i]];
      const Vec2& rest = mesh.rest[t[i]];
      u[2 * i] = c * x.x() + s * x.y() - rest.x(); // R^T x - X
      u[2 * i + 1] = -s * x.x() + c * x.y() - rest.y();
    }
    m_stress[tri] = m_material_stiffness[tri] * (m_strain[tri] * u);
    const Eigen::Matrix<double, 6, 1> local = m_stiffness[tri] * u;
    for (int i = 0; i < 3; ++i) {
      const double fx = local[2 * i], fy = local[2 * i + 1];
      forces[t[i]] -= Vec2(c * fx - s * fy, s * fx + c * fy);
    }
  }
}

void CorotationalElements::add_stiffness_times(const MembraneMesh& mesh, const std::vector<Vec2>& p,
                                               std::vector<Vec2>& out) const
{
  for (int tri = 0; tri < mesh.triangle_count(); ++tri) {
    const Triangle& t = mesh.triangles[tri];
    const double c = m_rotation[tri].x(), s = m_rotation[tri].y();
    Eigen::Matrix<double, 6, 1> local;
    for (int i = 0; i < 3; ++i) {
      const Vec2& q = p[t[i]];
      local[2 * i] = c * q.x() + s * q.y();
      local[2 * i + 1] = -s * q.x() + c * q.y();
    }
    const Eigen::Matrix<double, 6, 1> k = m_stiffness[tri] * local;
    for (int i = 0; i < 3; ++i) {
      const double kx = k[2 * i], ky = k[2 * i + 1];
      out[t[i]] += Vec2(c * kx - s * ky, s * kx + c * ky);
    }
  }
}

void CorotationalElements::add_stiffness_diagonal(const MembraneMesh& mesh,
                                                  std::vector<Vec2>& diagonal) const
{
  for (int tri = 0; tri < mesh.triangle_count(); ++tri) {
    const Triangle& t = mesh.triangles[tri];
    const double c = m_rotation[tri].x(), s = m_rotation[tri].y();
    const ElementMatrix& k = m_stiffness[tri];
    for (int i = 0; i < 3; ++i) {
      const double kxx = k(2 * i, 2 * i), kxy = k(2 * i, 2 * i + 1);
      const double kyy = k(2 * i + 1, 2 * i + 1);
      diagonal[t[i]] += Vec2(c * c * kxx - 2.0 * c * s * kxy + s * s * kyy,
                             s * s * kxx + 2.0 * c * s * kxy + c * c * kyy);
    }
  }
}

} // namespace ligsim::membrane
