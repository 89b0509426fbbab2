#pragma once
/// @brief Strain energy of one linear tet, W = F_G(I1) + F_C(I4) + F_V(J) (eq. 5-6), with the
/// forces and the 12x12 stiffness derived by hand through the node positions (eq. 7-24).

#include "sim/material/fiber_law.hpp"
#include "sim/material/material_parameters.hpp"
#include "sim/mesh/tet_shape.hpp"

#include <Eigen/Core>

#include <optional>

namespace ligsim::sim {

using Vector12d = Eigen::Matrix<double, 12, 1>;
using Matrix12d = Eigen::Matrix<double, 12, 12>;

/// How much of the element to compute.
enum class ElementNeeds { energy, gradient, hessian };

/// One element's energy and derivatives. Entries are node-major: 3 i + component.
struct ElementEvaluation {
  /// J <= 0 or not finite: nothing else is computed and the energy is +infinity.
  bool inverted = false;
  double J = 1.0;
  double energy = 0.0; ///< V0 W, N mm
  Vector12d gradient;  ///< dE/dQ, N (the internal force is its negative)
  Matrix12d hessian;   ///< d^2E/dQ^2, N/mm
};

/// Per-element figures for outputs.
struct ElementMeasures {
  double J = 1.0;
  double energy_density_mpa = 0.0; ///< W
  /// |F a|: the fiber's stretch including the in-situ pre-strain carried by |a| (sec. 2.7);
  /// 0 without fibers.
  double fiber_stretch = 0.0;
  /// Deviatoric stretch lambda = sqrt(I4) that the fiber law sees; 0 without fibers.
  double deviatoric_fiber_stretch = 0.0;
};

class WeissMaterial {
public:
  /// Validates `parameters` (InputError on a bad one).
  explicit WeissMaterial(const MaterialParameters& parameters);

  const MaterialParameters& parameters() const { return m_parameters; }
  bool has_fibers() const { return m_fiber_law.has_value(); }
  const FiberLaw* fiber_law() const { return m_fiber_law ? &*m_fiber_law : nullptr; }

  /// Evaluates the element with corners `Q` (mm). `fiber` is the element's fiber vector a
  /// (|a| = 1 + in-situ strain), ignored when the material has no fibers.
  void evaluate(const TetCorners& Q, const TetShape& shape, const Eigen::Vector3d& fiber,
                ElementNeeds needs, ElementEvaluation& out) const;

  ElementMeasures measures(const TetCorners& Q, const TetShape& shape,
                           const Eigen::Vector3d& fiber) const;

private:
  MaterialParameters m_parameters;
  std::optional<FiberLaw> m_fiber_law;
};

/// Replaces `H` by its projection onto the positive semi-definite cone (negative eigenvalues set
/// to zero). Returns true if anything was negative.
bool project_to_psd(Matrix12d& H);

} // namespace ligsim::sim
