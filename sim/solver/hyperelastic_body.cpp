#include "sim/solver/hyperelastic_body.hpp"

#include "common/error.hpp"
#include "sim/solver/parallel.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>

namespace ligsim::sim {

HyperelasticBody::HyperelasticBody(TetMesh mesh, const MaterialParameters& material,
                                   FiberField fibers)
    : m_mesh(std::move(mesh))
    , m_material(material)
    , m_shapes(compute_rest_shapes(m_mesh))
{
  if (m_material.has_fibers()) {
    if (fibers.rows() != 1 && fibers.rows() != m_mesh.T.rows())
      fail("the fiber field has {} vectors; expected 1 or one per element ({})", fibers.rows(),
           m_mesh.T.rows());
    for (Eigen::Index e = 0; e < fibers.rows(); ++e)
      if (!fibers.row(e).allFinite() || fibers.row(e).norm() < 1e-12)
        fail("the fiber vector of element {} is zero or not finite ({}, {}, {})", e, fibers(e, 0),
             fibers(e, 1), fibers(e, 2));
    for (Eigen::Index e = 0; e < fibers.rows(); ++e)
      m_fibers.emplace_back(fibers.row(e).transpose());
  }
  m_unreferenced.assign(static_cast<std::size_t>(m_mesh.V.rows()), true);
  for (Eigen::Index e = 0; e < m_mesh.T.rows(); ++e)
    for (int i = 0; i < 4; ++i)
      m_unreferenced[static_cast<std::size_t>(m_mesh.T(e, i))] = false;
  for (const TetShape& shape : m_shapes)
    m_rest_volume += shape.V0;
}

const Eigen::Vector3d& HyperelasticBody::fiber(Eigen::Index e) const
{
  if (m_fibers.empty())
    return m_no_fiber;
  return m_fibers[m_fibers.size() == 1 ? 0 : static_cast<std::size_t>(e)];
}

Eigen::VectorXd HyperelasticBody::rest_positions() const
{
  return Eigen::Map<const Eigen::VectorXd>(m_mesh.V.data(), dof_count());
}

BodyEnergy HyperelasticBody::energy(const Eigen::VectorXd& x) const
{
  std::vector<double> sums(static_cast<std::size_t>(worker_count()), 0.0);
  std::vector<int> inverted(sums.size(), std::numeric_limits<int>::max());
  parallel_slices(m_mesh.T.rows(), [&](std::ptrdiff_t begin, std::ptrdiff_t end, int worker) {
    ElementEvaluation evaluation;
    for (std::ptrdiff_t e = begin; e < end; ++e) {
      m_material.evaluate(tet_corners(m_mesh.T, e, x), shape(e), fiber(e), ElementNeeds::energy,
                          evaluation);
      if (evaluation.inverted)
        inverted[static_cast<std::size_t>(worker)] =
            std::min(inverted[static_cast<std::size_t>(worker)], static_cast<int>(e));
      else
        sums[static_cast<std::size_t>(worker)] += evaluation.energy;
    }
  });
  return finish_energy(x, sums, inverted);
}

BodyEnergy HyperelasticBody::energy_gradient(const Eigen::VectorXd& x,
                                             Eigen::VectorXd& gradient) const
{
  const std::size_t workers = static_cast<std::size_t>(worker_count());
  std::vector<double> sums(workers, 0.0);
  std::vector<int> inverted(workers, std::numeric_limits<int>::max());
  std::vector<Eigen::VectorXd> partial(workers);
  parallel_slices(m_mesh.T.rows(), [&](std::ptrdiff_t begin, std::ptrdiff_t end, int worker) {
    const std::size_t w = static_cast<std::size_t>(worker);
    Eigen::VectorXd& local = partial[w];
    local.setZero(dof_count());
    ElementEvaluation evaluation;
    for (std::ptrdiff_t e = begin; e < end; ++e) {
      m_material.evaluate(tet_corners(m_mesh.T, e, x), shape(e), fiber(e), ElementNeeds::gradient,
                          evaluation);
      if (evaluation.inverted) {
        inverted[w] = std::min(inverted[w], static_cast<int>(e));
        continue;
      }
      sums[w] += evaluation.energy;
      for (int i = 0; i < 4; ++i)
        local.segment<3>(3 * m_mesh.T(e, i)) += evaluation.gradient.segment<3>(3 * i);
    }
  });
  gradient.setZero(dof_count());
  for (const Eigen::VectorXd& local : partial)
    if (local.size() == gradient.size())
      gradient += local;
  return finish_energy(x, sums, inverted);
}

BodyEnergy HyperelasticBody::finish_energy(const Eigen::VectorXd& x,
                                           const std::vector<double>& sums,
                                           const std::vector<int>& inverted) const
{
  BodyEnergy result;
  for (double sum : sums)
    result.energy += sum;
  const int first = *std::min_element(inverted.begin(), inverted.end());
  if (first != std::numeric_limits<int>::max()) {
    result.first_inverted = first;
    result.inverted_j = measures(x, first).J;
    result.energy = std::numeric_limits<double>::infinity();
  }
  return result;
}

bool HyperelasticBody::element_hessian(const Eigen::VectorXd& x, Eigen::Index e, bool project,
                                       ElementEvaluation& out) const
{
  m_material.evaluate(tet_corners(m_mesh.T, e, x), shape(e), fiber(e), ElementNeeds::hessian, out);
  return project && !out.inverted && project_to_psd(out.hessian);
}

int HyperelasticBody::element_hessians(const Eigen::VectorXd& x, Eigen::Index begin,
                                       Eigen::Index end, bool project, Matrix12d* out) const
{
  std::vector<int> projected(static_cast<std::size_t>(worker_count()), 0);
  parallel_slices(end - begin, [&](std::ptrdiff_t first, std::ptrdiff_t last, int worker) {
    ElementEvaluation evaluation;
    for (std::ptrdiff_t k = first; k < last; ++k) {
      if (element_hessian(x, begin + k, project, evaluation))
        ++projected[static_cast<std::size_t>(worker)];
      out[k] = evaluation.hessian;
    }
  });
  int total = 0;
  for (int count : projected)
    total += count;
  return total;
}

ElementMeasures HyperelasticBody::measures(const Eigen::VectorXd& x, Eigen::Index e) const
{
  return m_material.measures(tet_corners(m_mesh.T, e, x), shape(e), fiber(e));
}

std::pair<double, int> HyperelasticBody::min_j(const Eigen::VectorXd& x) const
{
  double smallest = std::numeric_limits<double>::infinity();
  int where = -1;
  for (Eigen::Index e = 0; e < m_mesh.T.rows(); ++e) {
    const TetCorners Q = tet_corners(m_mesh.T, e, x);
    const double J = (Q.transpose() * shape(e).D).determinant();
    if (std::isnan(J))
      return {J, static_cast<int>(e)};
    if (J < smallest) {
      smallest = J;
      where = static_cast<int>(e);
    }
  }
  return {smallest, where};
}

double HyperelasticBody::volume(const Eigen::VectorXd& x) const
{
  double sum = 0.0;
  for (Eigen::Index e = 0; e < m_mesh.T.rows(); ++e) {
    const TetCorners Q = tet_corners(m_mesh.T, e, x);
    sum += shape(e).V0 * (Q.transpose() * shape(e).D).determinant();
  }
  return sum;
}

} // namespace ligsim::sim
