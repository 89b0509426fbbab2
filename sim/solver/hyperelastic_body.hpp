#pragma once
/// @brief A tet mesh of one Weiss material, linear (4-node) or quadratic (10-node) tets, with
/// its rest shapes and fiber vectors: total energy, gradient and element stiffnesses of a
/// configuration.

#include "common/mesh.hpp"
#include "sim/material/quadratic_tet_element.hpp"
#include "sim/material/weiss_material.hpp"
#include "sim/mesh/quadratic_tet.hpp"
#include "sim/mesh/tet_shape.hpp"
#include "sim/solver/parallel.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <limits>
#include <type_traits>
#include <vector>

namespace ligsim::sim {

/// Fiber vectors a (|a| = 1 + in-situ strain): a single row for all, one row per element, or,
/// for quadratic tets, one per quadrature point of every element (element-major).
using FiberField = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// Node indices of each element, one row per element: 4 columns (linear tets) or 10
/// (QuadraticTetrahedra's order).
using ElementNodes = Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// Energy of a configuration, with the first inverted element when there is one.
struct BodyEnergy {
  double energy = 0.0; ///< N mm; +infinity when an element is inverted
  int first_inverted = -1;
  double inverted_j = 1.0; ///< J of that element
};

class HyperelasticBody {
public:
  /// A body of linear tets. Validates the mesh (InputError naming the node or element) and the
  /// fibers: a material with fibers needs one row or one row per element, each finite and
  /// non-zero; a material without fibers ignores `fibers`.
  HyperelasticBody(TetMesh mesh, const MaterialParameters& material, FiberField fibers);
  /// A body of 10-node tets integrated with `rule`; the fibers as above, or one row per
  /// quadrature point of every element.
  HyperelasticBody(const QuadraticTetMesh& mesh, const MaterialParameters& material,
                   FiberField fibers, const QuadratureRule& rule);

  /// The tets of the elements' corners over all the nodes: a linear body's mesh; a quadratic
  /// body's mid-edge nodes are in V and in no tet.
  const TetMesh& mesh() const { return m_mesh; }
  /// Every element's nodes: its 4 corners, then a quadratic tet's 6 mid-edge nodes.
  const ElementNodes& elements() const { return m_elements; }
  int nodes_per_element() const { return static_cast<int>(m_elements.cols()); }
  bool quadratic() const { return nodes_per_element() == 10; }
  const WeissMaterial& material() const { return m_material; }
  int node_count() const { return static_cast<int>(m_mesh.V.rows()); }
  int element_count() const { return static_cast<int>(m_elements.rows()); }
  int dof_count() const { return 3 * node_count(); }
  /// Rest volume of element e, mm^3.
  double element_volume(Eigen::Index e) const;
  /// Rest shape of linear element e (a linear body only).
  const TetShape& shape(Eigen::Index e) const { return m_shapes[static_cast<std::size_t>(e)]; }
  /// Fiber vector of element e, at its first quadrature point for a quadratic tet (zero
  /// without fibers).
  const Eigen::Vector3d& fiber(Eigen::Index e) const;
  /// Nodes that no element uses: they carry no stiffness, so solvers hold them fixed.
  const std::vector<bool>& unreferenced_nodes() const { return m_unreferenced; }
  /// Total rest volume, mm^3.
  double rest_volume() const { return m_rest_volume; }

  /// Rest positions, flat (3 #nodes), mm.
  Eigen::VectorXd rest_positions() const;
  /// A body of the same elements (and rule) with rest positions `rest` (#nodes x 3, mm), one
  /// fiber per element `fibers` and `material`.
  HyperelasticBody with(const Points& rest, FiberField fibers,
                        const MaterialParameters& material) const;

  /// Calls f(std::integral_constant<int, N>{}) with N the nodes per element, 4 or 10, so that
  /// element loops are compiled for each size.
  template <class F> decltype(auto) with_element_size(F&& f) const
  {
    if (quadratic())
      return f(std::integral_constant<int, 10>{});
    return f(std::integral_constant<int, 4>{});
  }

  /// Energy and derivatives of element e at `x`, N its nodes (nodes_per_element()).
  template <int N>
  void evaluate(const Eigen::VectorXd& x, Eigen::Index e, ElementNeeds needs,
                NodalEvaluation<N>& out) const;

  BodyEnergy energy(const Eigen::VectorXd& x) const;
  /// Energy and its gradient dE/dx (flat, N); the gradient is meaningless when inverted.
  BodyEnergy energy_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& gradient) const;

  /// Energy, gradient and stiffness of element e into `out` (the stiffness projected to positive
  /// semi-definite when `project`); returns whether it needed the projection. `out.inverted`
  /// says whether the element is inverted (then nothing else is computed).
  template <int N>
  bool element_hessian(const Eigen::VectorXd& x, Eigen::Index e, bool project,
                       NodalEvaluation<N>& out) const;
  /// One parallel pass computing every element's stiffness (projected to positive
  /// semi-definite when `project`; `projected` counts those that needed it) and handing it to
  /// visit(e, H, worker) on its worker (contiguous slices of the elements, in order; workers
  /// 0 .. worker_count() - 1), H a 3N x 3N matrix, with the energy and, when `gradient` is
  /// given, the gradient exactly as energy_gradient() gives them. Inverted elements are not
  /// visited.
  template <class Visit>
  BodyEnergy stiffness_pass(const Eigen::VectorXd& x, bool project, Eigen::VectorXd* gradient,
                            int& projected, Visit&& visit) const;
  /// Stiffness of elements [begin, end) into out, (3N)^2 values each (column-major, N the
  /// nodes per element), each projected to positive semi-definite when `project`; returns how
  /// many needed the projection. `x` must have no inverted element.
  int element_hessians(const Eigen::VectorXd& x, Eigen::Index begin, Eigen::Index end, bool project,
                       double* out) const;

  /// K(x) d for a motion d (flat, 3 #nodes), unprojected, summed over `elements` (all when
  /// null) in their order; elements that d does not move are skipped. `x` must have no
  /// inverted element.
  Eigen::VectorXd apply_stiffness(const Eigen::VectorXd& x, const Eigen::VectorXd& d,
                                  const std::vector<int>* elements = nullptr) const;

  /// Element e's figures; for a quadratic tet, their volume-weighted mean over its points.
  ElementMeasures measures(const Eigen::VectorXd& x, Eigen::Index e) const;
  /// Smallest J over the elements (over every quadrature point of a quadratic tet) and where it
  /// is (the first NaN if any).
  std::pair<double, int> min_j(const Eigen::VectorXd& x) const;
  /// Deformed volume, mm^3.
  double volume(const Eigen::VectorXd& x) const;

private:
  void set_up(const FiberField& fibers, Eigen::Index fiber_rows_per_element);
  /// Sums per-worker energies; +infinity and the first inverted element if any.
  BodyEnergy finish_energy(const Eigen::VectorXd& x, const std::vector<double>& sums,
                           const std::vector<int>& inverted) const;
  /// The fiber at point q of element e.
  const Eigen::Vector3d& point_fiber(Eigen::Index e, std::size_t q) const;
  /// Calls f(F, weight, fiber) at each point of element e: a linear tet's one (weight V0),
  /// a quadratic tet's quadrature points.
  template <class F> void for_each_point(const Eigen::VectorXd& x, Eigen::Index e, F&& f) const;
  /// One parallel pass over the elements, N nodes each: their energy, the gradient when
  /// `gradient` is given, and with `needs` = hessian each one's stiffness handed to `visit`
  /// (see stiffness_pass).
  template <int N, class Visit>
  BodyEnergy element_pass(const Eigen::VectorXd& x, ElementNeeds needs, bool project,
                          Eigen::VectorXd* gradient, int& projected, Visit&& visit) const;

  TetMesh m_mesh;
  ElementNodes m_elements;
  WeissMaterial m_material;
  std::vector<TetShape> m_shapes;                    ///< linear tets
  std::vector<QuadraticTetShape> m_quadratic_shapes; ///< quadratic tets
  QuadratureRule m_rule;                             ///< quadratic tets
  /// Fibers: empty, one, one per element, or (quadratic) one per point of every element.
  std::vector<Eigen::Vector3d> m_fibers;
  int m_fibers_per_element = 0; ///< 0: one for all
  std::vector<bool> m_unreferenced;
  double m_rest_volume = 0.0;
  Eigen::Vector3d m_no_fiber = Eigen::Vector3d::Zero();
};

template <class F>
void HyperelasticBody::for_each_point(const Eigen::VectorXd& x, Eigen::Index e, F&& f) const
{
  if (!quadratic()) {
    f(tet_corners(m_mesh.T, e, x).transpose() * shape(e).D, shape(e).V0, fiber(e));
    return;
  }
  QuadraticTetRows Q;
  for (int i = 0; i < 10; ++i)
    Q.row(i) = x.template segment<3>(3 * m_elements(e, i)).transpose();
  const QuadraticTetShape& shape = m_quadratic_shapes[static_cast<std::size_t>(e)];
  for (std::size_t q = 0; q < shape.points.size(); ++q)
    f(Q.transpose() * shape.points[q].G, shape.points[q].weight, point_fiber(e, q));
}

template <class Visit>
BodyEnergy HyperelasticBody::stiffness_pass(const Eigen::VectorXd& x, bool project,
                                            Eigen::VectorXd* gradient, int& projected,
                                            Visit&& visit) const
{
  return with_element_size([&](auto size) {
    return element_pass<decltype(size)::value>(x, ElementNeeds::hessian, project, gradient,
                                               projected, visit);
  });
}

template <int N, class Visit>
BodyEnergy HyperelasticBody::element_pass(const Eigen::VectorXd& x, ElementNeeds needs,
                                          bool project, Eigen::VectorXd* gradient, int& projected,
                                          Visit&& visit) const
{
  const std::size_t workers = static_cast<std::size_t>(worker_count());
  std::vector<double> sums(workers, 0.0);
  std::vector<int> inverted(workers, std::numeric_limits<int>::max());
  std::vector<int> projections(workers, 0);
  std::vector<Eigen::VectorXd> partial(gradient ? workers : 0);
  parallel_slices(m_elements.rows(), [&](std::ptrdiff_t begin, std::ptrdiff_t end, int worker) {
    const std::size_t w = static_cast<std::size_t>(worker);
    if (gradient)
      partial[w].setZero(dof_count());
    NodalEvaluation<N> evaluation;
    for (std::ptrdiff_t e = begin; e < end; ++e) {
      if (needs == ElementNeeds::hessian)
        projections[w] += element_hessian<N>(x, e, project, evaluation) ? 1 : 0;
      else
        evaluate<N>(x, e, needs, evaluation);
      if (evaluation.inverted) {
        inverted[w] = std::min(inverted[w], static_cast<int>(e));
        continue;
      }
      sums[w] += evaluation.energy;
      if (gradient)
        for (int i = 0; i < N; ++i)
          partial[w].template segment<3>(3 * m_elements(e, i)) +=
              evaluation.gradient.template segment<3>(3 * i);
      if (needs == ElementNeeds::hessian)
        visit(e, evaluation.hessian, worker);
    }
  });
  if (gradient) {
    gradient->setZero(dof_count());
    for (const Eigen::VectorXd& local : partial)
      if (local.size() == gradient->size())
        *gradient += local;
  }
  projected = 0;
  for (int count : projections)
    projected += count;
  return finish_energy(x, sums, inverted);
}

} // namespace ligsim::sim
