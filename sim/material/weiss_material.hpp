#pragma once
/// @brief Strain energy W = F_G(I1) + F_C(I4) + F_V(J) (eq. 5-6) of one linear tet, or of one
/// quadrature point of a higher-order element, with the forces and the stiffness derived by
/// hand through the node positions (eq. 7-24).

#include "sim/material/fiber_law.hpp"
#include "sim/material/material_parameters.hpp"
#include "sim/material/volumetric_law.hpp"
#include "sim/mesh/tet_shape.hpp"

#include <Eigen/Core>

#include <optional>

namespace ligsim::sim {

using Vector12d = Eigen::Matrix<double, 12, 1>;
using Matrix12d = Eigen::Matrix<double, 12, 12>;

/// Positions or shape-function gradients of an element's N nodes, row i = node i.
template <int N> using NodeRows = Eigen::Matrix<double, N, 3, Eigen::RowMajor>;

/// How much of the element to compute.
enum class ElementNeeds { energy, gradient, hessian };

/// The energy and derivatives of an element of N nodes. Entries are node-major: 3 i + component.
template <int N> struct NodalEvaluation {
  /// J <= 0 or not finite: nothing else is computed and the energy is +infinity.
  bool inverted = false;
  double J = 1.0;      ///< at the point; the smallest over the points for a whole element
  double energy = 0.0; ///< integral of W, N mm
  Eigen::Matrix<double, 3 * N, 1> gradient;    ///< dE/dQ, N (the internal force is its negative)
  Eigen::Matrix<double, 3 * N, 3 * N> hessian; ///< d^2E/dQ^2, N/mm
};

/// One linear tet's energy and derivatives.
using ElementEvaluation = NodalEvaluation<4>;

/// Per-element figures for outputs.
struct ElementMeasures {
  double J = 1.0;
  double energy_density_mpa = 0.0; ///< W
  /// |F a|: the fiber's stretch including the in-situ pre-strain carried by |a| (sec. 2.7);
  /// 0 without fibers.
  double fiber_stretch = 0.0;
  /// Deviatoric stretch lambda = sqrt(I4) that the fiber law sees; 0 without fibers.
  double deviatoric_fiber_stretch = 0.0;
  /// F a, the fiber as deformed (its length the fiber stretch); zero without fibers.
  Eigen::Vector3d deformed_fiber = Eigen::Vector3d::Zero();
};

class WeissMaterial {
public:
  /// Validates `parameters` (InputError on a bad one).
  explicit WeissMaterial(const MaterialParameters& parameters);

  const MaterialParameters& parameters() const { return m_parameters; }
  bool has_fibers() const { return m_fiber_law.has_value(); }
  const FiberLaw* fiber_law() const { return m_fiber_law ? &*m_fiber_law : nullptr; }

  /// Evaluates the linear tet with corners `Q` (mm). `fiber` is the element's fiber vector a
  /// (|a| = 1 + in-situ strain), ignored when the material has no fibers.
  void evaluate(const TetCorners& Q, const TetShape& shape, const Eigen::Vector3d& fiber,
                ElementNeeds needs, ElementEvaluation& out) const;

  /// Evaluates W at one point of an element of N nodes at `Q` (mm), weighted by `weight` (mm^3):
  /// F = sum_i Q_i (outer) G_i, with G_i the gradient of node i's shape function in the rest
  /// shape at the point (1/mm). A linear tet is the case N = 4, G = D, weight = V0.
  /// Instantiated for N = 4 and 10.
  template <int N>
  void evaluate_at_point(const NodeRows<N>& Q, const NodeRows<N>& G, double weight,
                         const Eigen::Vector3d& fiber, ElementNeeds needs,
                         NodalEvaluation<N>& out) const;

  ElementMeasures measures(const TetCorners& Q, const TetShape& shape,
                           const Eigen::Vector3d& fiber) const;
  /// The same figures at deformation gradient F.
  ElementMeasures measures_at(const Eigen::Matrix3d& F, const Eigen::Vector3d& fiber) const;

private:
  /// W and the invariants it is made of at one deformation gradient (eq. 3, 6, 14, 22).
  struct PointState {
    bool inverted = false; ///< J not positive or not finite: nothing else is set
    double J = 1.0;
    double trace_c = 0.0; ///< tr C
    double s = 1.0;       ///< J^-2/3
    VolumetricResponse volumetric;
    Eigen::Vector3d fa = Eigen::Vector3d::Zero(); ///< F a
    double aca = 0.0;                             ///< a C a
    double lambda = 0.0;                          ///< deviatoric fiber stretch, sqrt(I4)
    FiberResponse fiber_response;
    double energy_density = 0.0; ///< W, MPa
  };
  PointState state_at(const Eigen::Matrix3d& F, const Eigen::Vector3d& fiber) const;

  MaterialParameters m_parameters;
  std::optional<FiberLaw> m_fiber_law;
};

/// Replaces an element's stiffness `H` (3 N x 3 N, N = 4 or 10 nodes) by a positive
/// semi-definite one: a linear tet's negative eigenvalues set to zero (the projection onto the
/// cone), a 10-node tet's to their absolute values (weiss_material.cpp says why). Returns true
/// if anything was negative.
template <int Size> bool project_to_psd(Eigen::Matrix<double, Size, Size>& H);

} // namespace ligsim::sim
