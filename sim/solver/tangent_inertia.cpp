#include "sim/solver/tangent_inertia.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace ligsim::sim {

namespace {

/// Inverse iterations: the eigenvalue nearest zero is well separated near a critical point.
constexpr int inverse_iterations = 30;
/// Below this load alignment a mode counts as orthogonal to the load.
constexpr double bifurcation_alignment = 0.1;

} // namespace

std::string StabilityMode::kind() const
{
  return load_alignment < bifurcation_alignment ? "bifurcation" : "limit point";
}

std::string StabilityMode::describe() const
{
  return fmt::format("{} ({} negative eigenvalue{} of the tangent stiffness, the one nearest "
                     "zero {:.3g} N/mm; mode orthogonal to the load to {:.2f}, largest at node "
                     "{} along ({:.2f}, {:.2f}, {:.2f}))",
                     kind(), negative_eigenvalues, negative_eigenvalues == 1 ? "" : "s", eigenvalue,
                     load_alignment, peak_node, peak_direction.x(), peak_direction.y(),
                     peak_direction.z());
}

TangentInertia::TangentInertia(const HyperelasticBody& body, const DofPartition& dofs)
    : TangentInertia(body, dofs, nullptr)
{
}

TangentInertia::TangentInertia(const HyperelasticBody& body, const DofPartition& dofs,
                               DirectCholesky* shared)
    : m_body(body)
    , m_dofs(dofs)
    , m_direct(shared)
{
}

TangentInertia::~TangentInertia() = default;

bool TangentInertia::factorize(const Eigen::VectorXd& x)
{
  if (!m_direct) {
    m_own = std::make_unique<DirectCholesky>(m_body, m_dofs);
    m_direct = m_own.get();
  }
  if (m_direct->holds_tangent(x)) {
    m_ok = true;
    return m_ok;
  }
  m_direct->prepare(m_body, x, false, 1.0, Eigen::VectorXd(), {});
  m_ok = m_direct->factorize();
  ++m_factorizations;
  return m_ok;
}

int TangentInertia::negative_eigenvalues() const
{
  return m_ok ? m_direct->factor().negative_pivots() : -1;
}

Eigen::VectorXd TangentInertia::solve(const Eigen::VectorXd& b) const
{
  return m_ok ? m_direct->factor().solve(b) : Eigen::VectorXd();
}

StabilityMode TangentInertia::lowest_mode(const Eigen::VectorXd& load) const
{
  StabilityMode mode;
  mode.negative_eigenvalues = negative_eigenvalues();
  if (!m_ok)
    return mode;
  const Eigen::Index n = m_dofs.free_count();
  // A fixed, non-symmetric start so the result does not depend on a random seed and is not
  // orthogonal to a symmetric or antisymmetric mode.
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i)
    v(i) = 1.0 + 0.5 * std::sin(1.7 * static_cast<double>(i));
  v.normalize();
  Eigen::VectorXd Kv;
  for (int k = 0; k < inverse_iterations; ++k) {
    Eigen::VectorXd w = solve(v);
    if (!w.allFinite() || w.norm() == 0.0)
      break;
    v = w.normalized();
  }
  m_direct->multiply(v, Kv);
  mode.eigenvalue = v.dot(Kv);
  mode.load_alignment = load.norm() > 0.0 ? std::abs(v.dot(load)) / load.norm() : 0.0;
  const Eigen::VectorXd full = m_dofs.expand(v);
  double peak = -1.0;
  for (int node = 0; node < m_dofs.dof_count() / 3; ++node) {
    const double size = full.segment<3>(3 * node).norm();
    if (size > peak) {
      peak = size;
      mode.peak_node = node;
      mode.peak_direction = size > 0.0 ? full.segment<3>(3 * node) / size : Eigen::Vector3d();
    }
  }
  return mode;
}

} // namespace ligsim::sim
