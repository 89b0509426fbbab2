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
    , m_elements(m_mesh.T)
    , m_material(material)
    , m_shapes(compute_rest_shapes(m_mesh))
{
  for (const TetShape& shape : m_shapes)
    m_rest_volume += shape.V0;
  set_up(fibers, 1);
}

HyperelasticBody::HyperelasticBody(const QuadraticTetMesh& mesh, const MaterialParameters& material,
                                   FiberField fibers, const QuadratureRule& rule)
    : m_elements(mesh.T)
    , m_material(material)
    , m_quadratic_shapes(compute_rest_shapes(mesh, rule))
    , m_rule(rule)
{
  m_mesh.V = mesh.V;
  m_mesh.T = mesh.T.leftCols<4>();
  for (const QuadraticTetShape& shape : m_quadratic_shapes)
    m_rest_volume += shape.V0;
  set_up(fibers, static_cast<Eigen::Index>(rule.points.size()));
}

void HyperelasticBody::set_up(const FiberField& fibers, Eigen::Index fiber_rows_per_element)
{
  const Eigen::Index elements = m_elements.rows();
  if (m_material.has_fibers()) {
    const Eigen::Index rows = fibers.rows();
    if (rows == 1)
      m_fibers_per_element = 0;
    else if (rows == elements)
      m_fibers_per_element = 1;
    else if (rows == elements * fiber_rows_per_element)
      m_fibers_per_element = static_cast<int>(fiber_rows_per_element);
    else if (fiber_rows_per_element == 1)
      fail("the fiber field has {} vectors; expected 1 or one per element ({})", rows, elements);
    else
      fail("the fiber field has {} vectors; expected 1, one per element ({}) or one per "
           "quadrature point ({})",
           rows, elements, elements * fiber_rows_per_element);
    for (Eigen::Index e = 0; e < rows; ++e)
      if (!fibers.row(e).allFinite() || fibers.row(e).norm() < 1e-12)
        fail("the fiber vector of element {} is zero or not finite ({}, {}, {})", e, fibers(e, 0),
             fibers(e, 1), fibers(e, 2));
    for (Eigen::Index e = 0; e < rows; ++e)
      m_fibers.emplace_back(fibers.row(e).transpose());
  }
  m_unreferenced.assign(static_cast<std::size_t>(m_mesh.V.rows()), true);
  for (Eigen::Index e = 0; e < elements; ++e)
    for (Eigen::Index i = 0; i < m_elements.cols(); ++i)
      m_unreferenced[static_cast<std::size_t>(m_elements(e, i))] = false;
}

HyperelasticBody HyperelasticBody::with(const Points& rest, FiberField fibers,
                                        const MaterialParameters& material) const
{
  if (!quadratic())
    return HyperelasticBody(TetMesh{rest, m_mesh.T}, material, std::move(fibers));
  return HyperelasticBody(QuadraticTetMesh{rest, m_elements}, material, std::move(fibers), m_rule);
}

double HyperelasticBody::element_volume(Eigen::Index e) const
{
  const auto k = static_cast<std::size_t>(e);
  return quadratic() ? m_quadratic_shapes[k].V0 : m_shapes[k].V0;
}

const Eigen::Vector3d& HyperelasticBody::fiber(Eigen::Index e) const
{
  if (m_fibers.empty())
    return m_no_fiber;
  return m_fibers[static_cast<std::size_t>(e) * static_cast<std::size_t>(m_fibers_per_element)];
}

Eigen::VectorXd HyperelasticBody::rest_positions() const
{
  return Eigen::Map<const Eigen::VectorXd>(m_mesh.V.data(), dof_count());
}

template <>
void HyperelasticBody::evaluate<4>(const Eigen::VectorXd& x, Eigen::Index e, ElementNeeds needs,
                                   NodalEvaluation<4>& out) const
{
  m_material.evaluate(tet_corners(m_mesh.T, e, x), shape(e), fiber(e), needs, out);
}

template <>
void HyperelasticBody::evaluate<10>(const Eigen::VectorXd& x, Eigen::Index e, ElementNeeds needs,
                                    NodalEvaluation<10>& out) const
{
  const QuadraticTetShape& shape = m_quadratic_shapes[static_cast<std::size_t>(e)];
  QuadraticTetRows Q;
  for (int i = 0; i < 10; ++i)
    Q.row(i) = x.segment<3>(3 * m_elements(e, i)).transpose();
  // One fiber for the element, or one per point, consecutive from the first.
  evaluate_quadratic_tet(m_material, Q, shape, &point_fiber(e, 0),
                         m_fibers_per_element <= 1 ? 1 : m_fibers_per_element, needs, out);
}

BodyEnergy HyperelasticBody::energy(const Eigen::VectorXd& x) const
{
  int projected = 0;
  return with_element_size([&](auto size) {
    return element_pass<decltype(size)::value>(x, ElementNeeds::energy, false, nullptr, projected,
                                               [](Eigen::Index, const auto&, int) {});
  });
}

BodyEnergy HyperelasticBody::energy_gradient(const Eigen::VectorXd& x,
                                             Eigen::VectorXd& gradient) const
{
  int projected = 0;
  return with_element_size([&](auto size) {
    return element_pass<decltype(size)::value>(x, ElementNeeds::gradient, false, &gradient,
                                               projected, [](Eigen::Index, const auto&, int) {});
  });
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

template <int N>
bool HyperelasticBody::element_hessian(const Eigen::VectorXd& x, Eigen::Index e, bool project,
                                       NodalEvaluation<N>& out) const
{
  evaluate<N>(x, e, ElementNeeds::hessian, out);
  return project && !out.inverted && project_to_psd(out.hessian);
}

template bool HyperelasticBody::element_hessian<4>(const Eigen::VectorXd&, Eigen::Index, bool,
                                                   NodalEvaluation<4>&) const;
template bool HyperelasticBody::element_hessian<10>(const Eigen::VectorXd&, Eigen::Index, bool,
                                                    NodalEvaluation<10>&) const;

int HyperelasticBody::element_hessians(const Eigen::VectorXd& x, Eigen::Index begin,
                                       Eigen::Index end, bool project, double* out) const
{
  return with_element_size([&](auto size) {
    constexpr int N = decltype(size)::value;
    constexpr std::ptrdiff_t stride = 9 * N * N;
    std::vector<int> projected(static_cast<std::size_t>(worker_count()), 0);
    parallel_slices(end - begin, [&](std::ptrdiff_t first, std::ptrdiff_t last, int worker) {
      NodalEvaluation<N> evaluation;
      for (std::ptrdiff_t k = first; k < last; ++k) {
        if (element_hessian<N>(x, begin + k, project, evaluation))
          ++projected[static_cast<std::size_t>(worker)];
        Eigen::Map<Eigen::Matrix<double, 3 * N, 3 * N>>(out + k * stride) = evaluation.hessian;
      }
    });
    int total = 0;
    for (int count : projected)
      total += count;
    return total;
  });
}

Eigen::VectorXd HyperelasticBody::apply_stiffness(const Eigen::VectorXd& x,
                                                  const Eigen::VectorXd& d,
                                                  const std::vector<int>* elements) const
{
  return with_element_size([&](auto size) {
    constexpr int N = decltype(size)::value;
    using Vector = Eigen::Matrix<double, 3 * N, 1>;
    Eigen::VectorXd y = Eigen::VectorXd::Zero(d.size());
    NodalEvaluation<N> element;
    const Eigen::Index count =
        elements ? static_cast<Eigen::Index>(elements->size()) : m_elements.rows();
    for (Eigen::Index k = 0; k < count; ++k) {
      const Eigen::Index e = elements ? (*elements)[static_cast<std::size_t>(k)] : k;
      Vector local;
      for (int i = 0; i < N; ++i)
        local.template segment<3>(3 * i) = d.segment<3>(3 * m_elements(e, i));
      if (local.template lpNorm<Eigen::Infinity>() == 0.0)
        continue;
      evaluate<N>(x, e, ElementNeeds::hessian, element);
      const Vector force = element.hessian * local;
      for (int i = 0; i < N; ++i)
        y.segment<3>(3 * m_elements(e, i)) += force.template segment<3>(3 * i);
    }
    return y;
  });
}

const Eigen::Vector3d& HyperelasticBody::point_fiber(Eigen::Index e, std::size_t q) const
{
  if (m_fibers_per_element <= 1)
    return fiber(e);
  return m_fibers[static_cast<std::size_t>(e) * static_cast<std::size_t>(m_fibers_per_element) + q];
}

ElementMeasures HyperelasticBody::measures(const Eigen::VectorXd& x, Eigen::Index e) const
{
  if (!quadratic())
    return m_material.measures(tet_corners(m_mesh.T, e, x), shape(e), fiber(e));
  const double V0 = element_volume(e);
  ElementMeasures mean;
  mean.J = 0.0;
  bool inverted = false;
  for_each_point(x, e, [&](const Eigen::Matrix3d& F, double weight, const Eigen::Vector3d& a) {
    if (inverted)
      return;
    const ElementMeasures point = m_material.measures_at(F, a);
    if (!(point.J > 0.0)) { // the figures of the first inverted point
      mean = point;
      inverted = true;
      return;
    }
    const double w = weight / V0;
    mean.J += w * point.J;
    mean.energy_density_mpa += w * point.energy_density_mpa;
    mean.fiber_stretch += w * point.fiber_stretch;
    mean.deviatoric_fiber_stretch += w * point.deviatoric_fiber_stretch;
    mean.deformed_fiber += w * point.deformed_fiber;
  });
  return mean;
}

std::pair<double, int> HyperelasticBody::min_j(const Eigen::VectorXd& x) const
{
  double smallest = std::numeric_limits<double>::infinity();
  int where = -1;
  bool nan = false;
  for (Eigen::Index e = 0; e < m_elements.rows() && !nan; ++e)
    for_each_point(x, e, [&](const Eigen::Matrix3d& F, double, const Eigen::Vector3d&) {
      const double J = F.determinant();
      if (nan)
        return;
      if (std::isnan(J)) {
        nan = true;
        smallest = J;
        where = static_cast<int>(e);
      } else if (J < smallest) {
        smallest = J;
        where = static_cast<int>(e);
      }
    });
  return {smallest, where};
}

double HyperelasticBody::volume(const Eigen::VectorXd& x) const
{
  double sum = 0.0;
  for (Eigen::Index e = 0; e < m_elements.rows(); ++e)
    for_each_point(x, e, [&](const Eigen::Matrix3d& F, double weight, const Eigen::Vector3d&) {
      sum += weight * F.determinant();
    });
  return sum;
}

} // namespace ligsim::sim
