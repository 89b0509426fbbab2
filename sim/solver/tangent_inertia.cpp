#include "sim/solver/tangent_inertia.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace ligsim::sim {

namespace {

constexpr Eigen::Index chunk_size = 4096;
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

CholmodLdlt::CholmodLdlt()
{
  cholmod().print = 0;
  cholmod().nmethods = 1;
  cholmod().method[0].ordering = CHOLMOD_METIS; // less fill than AMD on 3-D meshes
}

Eigen::VectorXd CholmodLdlt::pivots() const
{
  const cholmod_factor* L = m_cholmodFactor;
  if (!L || L->is_super || L->is_ll)
    return {};
  // Simplicial L D L^T: each column starts with its diagonal entry, which holds D.
  const auto* p = static_cast<const int*>(L->p);
  const auto* values = static_cast<const double*>(L->x);
  Eigen::VectorXd d(static_cast<Eigen::Index>(L->n));
  for (std::size_t j = 0; j < L->n; ++j)
    d(static_cast<Eigen::Index>(j)) = values[p[j]];
  return d;
}

TangentInertia::TangentInertia(const HyperelasticBody& body, const DofPartition& dofs)
    : m_body(body)
    , m_dofs(dofs)
    , m_stiffness(body.mesh().T, dofs)
    , m_chunk(static_cast<std::size_t>(std::min<Eigen::Index>(chunk_size, body.element_count())))
{
}

bool TangentInertia::factorize(const Eigen::VectorXd& x)
{
  m_stiffness.set_zero();
  const Eigen::Index count = m_body.element_count();
  for (Eigen::Index begin = 0; begin < count; begin += chunk_size) {
    const Eigen::Index end = std::min(count, begin + chunk_size);
    m_body.element_hessians(x, begin, end, false, m_chunk.data());
    for (Eigen::Index e = begin; e < end; ++e)
      m_stiffness.add_element(e, m_chunk[static_cast<std::size_t>(e - begin)]);
  }
  if (!m_analyzed) {
    m_ldlt.analyzePattern(m_stiffness.matrix());
    m_analyzed = true;
  }
  m_ldlt.factorize(m_stiffness.matrix());
  m_pivots = m_ldlt.info() == Eigen::Success ? m_ldlt.pivots() : Eigen::VectorXd();
  m_ok = m_pivots.size() == m_stiffness.matrix().rows() && m_pivots.allFinite() &&
         (m_pivots.array() != 0.0).all();
  return m_ok;
}

int TangentInertia::negative_eigenvalues() const
{
  return m_ok ? static_cast<int>((m_pivots.array() < 0.0).count()) : -1;
}

Eigen::VectorXd TangentInertia::solve(const Eigen::VectorXd& b) const
{
  return m_ldlt.solve(b);
}

StabilityMode TangentInertia::lowest_mode(const Eigen::VectorXd& load) const
{
  StabilityMode mode;
  mode.negative_eigenvalues = negative_eigenvalues();
  const Eigen::Index n = m_stiffness.matrix().rows();
  // A fixed, non-symmetric start so the result does not depend on a random seed and is not
  // orthogonal to a symmetric or antisymmetric mode.
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i)
    v(i) = 1.0 + 0.5 * std::sin(1.7 * static_cast<double>(i));
  v.normalize();
  Eigen::VectorXd Kv;
  for (int k = 0; k < inverse_iterations; ++k) {
    Eigen::VectorXd w = m_ldlt.solve(v);
    if (!w.allFinite() || w.norm() == 0.0)
      break;
    v = w.normalized();
  }
  m_stiffness.multiply(v, Kv);
  mode.eigenvalue = v.dot(Kv);
  mode.load_alignment = load.norm() > 0.0 ? std::abs(v.dot(load)) / load.norm() : 0.0;
  const auto& free_dofs = m_dofs.free_dofs();
  Eigen::VectorXd full = Eigen::VectorXd::Zero(m_dofs.dof_count());
  for (std::size_t f = 0; f < free_dofs.size(); ++f)
    full(free_dofs[f]) = v(static_cast<Eigen::Index>(f));
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
