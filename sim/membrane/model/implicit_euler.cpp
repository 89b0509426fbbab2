#include "sim/membrane/model/implicit_euler.hpp"

#include "common/error.hpp"

#include <cmath>

namespace ligsim::membrane {
namespace {

double dot(const std::vector<Vec2>& a, const std::vector<Vec2>& b)
{
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
    sum += a[i].dot(b[i]);
  return sum;
}

bool is_free(const MembraneMesh& mesh, int v)
{
  return mesh.constraint[v] == NodeConstraint::free;
}

} // namespace

void validate(const SolverSettings& s, const char* where)
{
  if (!(s.time_step_s > 0.0) || !std::isfinite(s.time_step_s))
    fail("{}: time_step_s must be positive, got {}", where, s.time_step_s);
  if (!(s.mass_damping_per_s >= 0.0) || !(s.stiffness_damping_s >= 0.0))
    fail("{}: damping must not be negative (mass {} 1/s, stiffness {} s)", where,
         s.mass_damping_per_s, s.stiffness_damping_s);
  if (!(s.cg_tolerance > 0.0) || s.cg_max_iterations < 1)
    fail("{}: cg_tolerance must be positive and cg_max_iterations at least 1", where);
}

void ImplicitEuler::apply_system(const MembraneMesh& mesh, const CorotationalElements& elements,
                                 const std::vector<Vec2>& p, std::vector<Vec2>& out)
{
  const double h = m_settings.time_step_s;
  const double mass_factor = 1.0 + h * m_settings.mass_damping_per_s;
  const double stiffness_factor = h * m_settings.stiffness_damping_s + h * h;
  std::fill(out.begin(), out.end(), Vec2::Zero());
  elements.add_stiffness_times(mesh, p, out);
  for (int v = 0; v < mesh.node_count(); ++v)
    out[v] = is_free(mesh, v) ? Vec2(mass_factor * mesh.mass[v] * p[v] + stiffness_factor * out[v])
                              : Vec2::Zero();
}

SolveReport ImplicitEuler::step(MembraneMesh& mesh, CorotationalElements& elements,
                                const std::vector<Vec2>& external_forces)
{
  const int n = mesh.node_count();
  const double h = m_settings.time_step_s;
  const double a = m_settings.mass_damping_per_s, b = m_settings.stiffness_damping_s;
  for (auto* vector :
       {&m_force, &m_rhs, &m_diagonal, &m_dv, &m_residual, &m_search, &m_product, &m_z})
    vector->assign(n, Vec2::Zero());

  // Right-hand side h (f - a M v - (b + h) K v).
  m_force = external_forces;
  elements.add_forces(mesh, m_force);
  elements.add_stiffness_times(mesh, mesh.velocity, m_product);
  for (int v = 0; v < n; ++v)
    m_rhs[v] = h * (m_force[v] - a * mesh.mass[v] * mesh.velocity[v] - (b + h) * m_product[v]);

  // Jacobi preconditioner and the warm start.
  elements.add_stiffness_diagonal(mesh, m_diagonal);
  for (int v = 0; v < n; ++v) {
    m_diagonal[v] = ((1.0 + h * a) * mesh.mass[v] * Vec2::Ones() + (h * b + h * h) * m_diagonal[v]);
    m_dv[v] = is_free(mesh, v) ? mesh.last_velocity_change[v]
                               : Vec2(mesh.prescribed_velocity[v] - mesh.velocity[v]);
  }
  // The prescribed part enters the residual of the free rows through the coupling K_fc.
  std::fill(m_product.begin(), m_product.end(), Vec2::Zero());
  elements.add_stiffness_times(mesh, m_dv, m_product);
  double rhs_norm_squared = 0.0;
  for (int v = 0; v < n; ++v) {
    if (!is_free(mesh, v)) {
      m_residual[v].setZero();
      continue;
    }
    const Vec2 applied = (1.0 + h * a) * mesh.mass[v] * m_dv[v] + (h * b + h * h) * m_product[v];
    m_residual[v] = m_rhs[v] - applied;
    rhs_norm_squared += m_rhs[v].squaredNorm();
  }

  SolveReport report;
  const double target = m_settings.cg_tolerance * std::sqrt(rhs_norm_squared);
  for (int v = 0; v < n; ++v)
    m_search[v] = m_z[v] = m_residual[v].cwiseQuotient(m_diagonal[v]);
  double rz = dot(m_residual, m_z);
  double residual_norm = std::sqrt(dot(m_residual, m_residual));
  while (residual_norm > target && report.iterations < m_settings.cg_max_iterations) {
    apply_system(mesh, elements, m_search, m_product);
    const double curvature = dot(m_search, m_product);
    if (!(curvature > 0.0))
      break; // the search direction vanished: nothing left to reduce
    const double alpha = rz / curvature;
    for (int v = 0; v < n; ++v) {
      m_dv[v] += alpha * m_search[v];
      m_residual[v] -= alpha * m_product[v];
      m_z[v] = m_residual[v].cwiseQuotient(m_diagonal[v]);
    }
    const double rz_next = dot(m_residual, m_z);
    const double beta = rz_next / rz;
    rz = rz_next;
    for (int v = 0; v < n; ++v)
      m_search[v] = m_z[v] + beta * m_search[v];
    residual_norm = std::sqrt(dot(m_residual, m_residual));
    ++report.iterations;
  }
  report.relative_residual =
      rhs_norm_squared > 0.0 ? residual_norm / std::sqrt(rhs_norm_squared) : 0.0;

  for (int v = 0; v < n; ++v) {
    mesh.velocity[v] += m_dv[v];
    mesh.position[v] += h * mesh.velocity[v];
    mesh.last_velocity_change[v] = is_free(mesh, v) ? m_dv[v] : Vec2::Zero();
    if (!std::isfinite(mesh.position[v].x()) || !std::isfinite(mesh.position[v].y()))
      fail<SolverError>("membrane node {} left the finite numbers (time step {} s too large?)", v,
                        h);
  }
  return report;
}

} // namespace ligsim::membrane
