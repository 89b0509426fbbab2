#pragma once
/// @brief A tet mesh of one Weiss material with its rest shapes and fiber vectors: total energy,
/// gradient and element stiffnesses of a configuration.

#include "common/mesh.hpp"
#include "sim/material/weiss_material.hpp"
#include "sim/mesh/tet_shape.hpp"
#include "sim/solver/parallel.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <limits>
#include <vector>

namespace ligsim::sim {

/// Fiber vectors a, one row per element or a single row for all (|a| = 1 + in-situ strain).
using FiberField = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// Energy of a configuration, with the first inverted element when there is one.
struct BodyEnergy {
  double energy = 0.0; ///< N mm; +infinity when an element is inverted
  int first_inverted = -1;
  double inverted_j = 1.0; ///< J of that element
};

class HyperelasticBody {
public:
  /// Validates the mesh (InputError naming the node or element) and the fibers: a material with
  /// fibers needs one row or one row per element, each finite and non-zero; a material without
  /// fibers ignores `fibers`.
  HyperelasticBody(TetMesh mesh, const MaterialParameters& material, FiberField fibers);

  const TetMesh& mesh() const { return m_mesh; }
  const WeissMaterial& material() const { return m_material; }
  int node_count() const { return static_cast<int>(m_mesh.V.rows()); }
  int element_count() const { return static_cast<int>(m_mesh.T.rows()); }
  int dof_count() const { return 3 * node_count(); }
  const TetShape& shape(Eigen::Index e) const { return m_shapes[static_cast<std::size_t>(e)]; }
  /// Fiber vector of element e (zero without fibers).
  const Eigen::Vector3d& fiber(Eigen::Index e) const;
  /// Nodes that no element uses: they carry no stiffness, so solvers hold them fixed.
  const std::vector<bool>& unreferenced_nodes() const { return m_unreferenced; }
  /// Total rest volume, mm^3.
  double rest_volume() const { return m_rest_volume; }

  /// Rest positions, flat (3 #nodes), mm.
  Eigen::VectorXd rest_positions() const;

  BodyEnergy energy(const Eigen::VectorXd& x) const;
  /// Energy and its gradient dE/dx (flat, N); the gradient is meaningless when inverted.
  BodyEnergy energy_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& gradient) const;

  /// Energy, gradient and stiffness of element e into `out` (the stiffness projected to positive
  /// semi-definite when `project`); returns whether it needed the projection. `out.inverted`
  /// says whether the element is inverted (then nothing else is computed).
  bool element_hessian(const Eigen::VectorXd& x, Eigen::Index e, bool project,
                       ElementEvaluation& out) const;
  /// One parallel pass computing every element's stiffness (projected to positive
  /// semi-definite when `project`; `projected` counts those that needed it) and handing it to
  /// visit(e, H, worker) on its worker (contiguous slices of the elements, in order; workers
  /// 0 .. worker_count() - 1), with the energy and, when `gradient` is given, the gradient
  /// exactly as energy_gradient() gives them. Inverted elements are not visited.
  template <class Visit>
  BodyEnergy stiffness_pass(const Eigen::VectorXd& x, bool project, Eigen::VectorXd* gradient,
                            int& projected, Visit&& visit) const;
  /// Stiffness of elements [begin, end) into out[0 .. end - begin), each projected to positive
  /// semi-definite when `project`; returns how many needed the projection. `x` must have no
  /// inverted element.
  int element_hessians(const Eigen::VectorXd& x, Eigen::Index begin, Eigen::Index end, bool project,
                       Matrix12d* out) const;

  ElementMeasures measures(const Eigen::VectorXd& x, Eigen::Index e) const;
  /// Smallest J over the elements and where it is (the first NaN if any).
  std::pair<double, int> min_j(const Eigen::VectorXd& x) const;
  /// Deformed volume, mm^3.
  double volume(const Eigen::VectorXd& x) const;

private:
  /// Sums per-worker energies; +infinity and the first inverted element if any.
  BodyEnergy finish_energy(const Eigen::VectorXd& x, const std::vector<double>& sums,
                           const std::vector<int>& inverted) const;

  TetMesh m_mesh;
  WeissMaterial m_material;
  std::vector<TetShape> m_shapes;
  std::vector<Eigen::Vector3d> m_fibers; ///< empty, one, or one per element
  std::vector<bool> m_unreferenced;
  double m_rest_volume = 0.0;
  Eigen::Vector3d m_no_fiber = Eigen::Vector3d::Zero();
};

template <class Visit>
BodyEnergy HyperelasticBody::stiffness_pass(const Eigen::VectorXd& x, bool project,
                                            Eigen::VectorXd* gradient, int& projected,
                                            Visit&& visit) const
{
  const std::size_t workers = static_cast<std::size_t>(worker_count());
  std::vector<double> sums(workers, 0.0);
  std::vector<int> inverted(workers, std::numeric_limits<int>::max());
  std::vector<int> projections(workers, 0);
  std::vector<Eigen::VectorXd> partial(gradient ? workers : 0);
  parallel_slices(m_mesh.T.rows(), [&](std::ptrdiff_t begin, std::ptrdiff_t end, int worker) {
    const std::size_t w = static_cast<std::size_t>(worker);
    if (gradient)
      partial[w].setZero(dof_count());
    ElementEvaluation evaluation;
    for (std::ptrdiff_t e = begin; e < end; ++e) {
      projections[w] += element_hessian(x, e, project, evaluation) ? 1 : 0;
      if (evaluation.inverted) {
        inverted[w] = std::min(inverted[w], static_cast<int>(e));
        continue;
      }
      sums[w] += evaluation.energy;
      if (gradient)
        for (int i = 0; i < 4; ++i)
          partial[w].segment<3>(3 * m_mesh.T(e, i)) += evaluation.gradient.segment<3>(3 * i);
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
