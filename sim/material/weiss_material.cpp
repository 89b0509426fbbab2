#include "sim/material/weiss_material.hpp"

#include "sim/material/volumetric_law.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <cmath>
#include <limits>

namespace ligsim::sim {

namespace {

/// Cofactor matrix of F, dJ/dF: its columns are the cross products of F's other two columns.
Eigen::Matrix3d cofactor(const Eigen::Matrix3d& F)
{
  Eigen::Matrix3d C;
  C.col(0) = F.col(1).cross(F.col(2));
  C.col(1) = F.col(2).cross(F.col(0));
  C.col(2) = F.col(0).cross(F.col(1));
  return C;
}

template <int N> Eigen::Map<const Eigen::Matrix<double, 3 * N, 1>> flat(const NodeRows<N>& rows)
{
  return Eigen::Map<const Eigen::Matrix<double, 3 * N, 1>>(rows.data());
}

} // namespace

WeissMaterial::WeissMaterial(const MaterialParameters& parameters)
    : m_parameters(parameters)
{
  validate(parameters);
  if (parameters.fiber)
    m_fiber_law.emplace(*parameters.fiber);
}

void WeissMaterial::evaluate(const TetCorners& Q, const TetShape& shape,
                             const Eigen::Vector3d& fiber, ElementNeeds needs,
                             ElementEvaluation& out) const
{
  evaluate_at_point<4>(Q, shape.D, shape.V0, fiber, needs, out);
}

// D and V0 are the header's G and weight, named as eq. 1-24 name them for a linear tet.
template <int N>
void WeissMaterial::evaluate_at_point(const NodeRows<N>& Q, const NodeRows<N>& D, double V0,
                                      const Eigen::Vector3d& fiber, ElementNeeds needs,
                                      NodalEvaluation<N>& out) const
{
  using Rows = NodeRows<N>;
  // Eq. 2: deformation gradient F = sum_i Q_i (outer) D_i.
  const Eigen::Matrix3d F = Q.transpose() * D;
  const PointState state = state_at(F, fiber);
  out.J = state.J;
  out.inverted = state.inverted;
  if (out.inverted) {
    out.energy = std::numeric_limits<double>::infinity();
    return;
  }
  out.energy = V0 * state.energy_density;
  if (needs == ElementNeeds::energy)
    return;
  const double mu = m_parameters.mu_mpa;
  const double J = state.J;
  const double trace_c = state.trace_c;
  const double s = state.s;
  const VolumetricResponse& volumetric = state.volumetric;
  const Eigen::Vector3d& fa = state.fa;
  const double aca = state.aca;
  const double lambda = state.lambda;
  const FiberResponse& fiber_response = state.fiber_response;
  const bool fiber_active = m_fiber_law && lambda >= 1.0;

  // First derivatives of the scalar building blocks w.r.t. the 12 node coordinates:
  // dJ/dQ_i = cof(F) D_i (eq. 7: (b x c)/(6 V0)), d trC/dQ_i = 2 F D_i (eq. 10),
  // d aCa/dQ_i = 2 (a . D_i) F a (eq. 16).
  const Eigen::Matrix3d cof = cofactor(F);
  const Rows grad_j = D * cof.transpose();
  const Rows grad_tr = 2.0 * D * F.transpose();
  const double s_j = -2.0 / 3.0 * s / J;        // d J^-2/3 / dJ
  const double s_jj = 10.0 / 9.0 * s / (J * J); // d^2 J^-2/3 / dJ^2 (eq. 12)
  // dF_C/dI4 = F_C'(lambda) / (2 lambda) (eq. 15), and d^2F_C/dI4^2 (eq. 19).
  double phi = 0.0;
  double psi = 0.0;
  Eigen::Matrix<double, N, 1> a_dot_d = Eigen::Matrix<double, N, 1>::Zero();
  Rows grad_aca = Rows::Zero();
  if (fiber_active) {
    phi = fiber_response.d1 / (2.0 * lambda);
    psi = fiber_response.d2 / (4.0 * lambda * lambda) -
          fiber_response.d1 / (4.0 * lambda * lambda * lambda);
    a_dot_d = D * fiber;
    grad_aca = 2.0 * a_dot_d * fa.transpose();
  }

  // Gradient (eq. 11, 15-17, 23) collected per building block:
  // dW = mu/2 s dtrC + phi s daCa + (mu/2 trC + phi aCa) s_j dJ + F_V' dJ.
  const double scale_t = 0.5 * mu * s;
  const double scale_a = phi * s;
  const double through_j = (0.5 * mu * trace_c + phi * aca);
  const double scale_j = through_j * s_j + volumetric.d1;
  Rows gradient = scale_t * grad_tr + scale_j * grad_j;
  if (fiber_active)
    gradient += scale_a * grad_aca;
  out.gradient = V0 * flat<N>(gradient);
  if (needs == ElementNeeds::gradient)
    return;

  // Hessian (eq. 8, 12-13, 18-21, 24), grouped by the outer products it is made of:
  //   (through_j s_jj + F_V'') dJ dJ^T                     second derivative of J^-2/3, F_V
  // + u dJ^T + dJ u^T, u = s_j (mu/2 dtrC + phi daCa)       cross terms of eq. 13 and 20
  // + psi v v^T, v = dI4 = s daCa + aCa s_j dJ             eq. 19, first term
  // + (through_j s_j + F_V') d^2J                           eq. 8, 12, 24
  // + (mu s (D_i . D_j) + 2 phi s (a . D_i)(a . D_j)) 1      eq. 12 and 21
  const auto dj = flat<N>(grad_j);
  Rows u_rows = s_j * 0.5 * mu * grad_tr;
  if (fiber_active)
    u_rows += s_j * phi * grad_aca;
  const auto u = flat<N>(u_rows);
  auto& H = out.hessian;
  H.noalias() = (through_j * s_jj + volumetric.d2) * dj * dj.transpose();
  H.noalias() += u * dj.transpose();
  H.noalias() += dj * u.transpose();
  if (fiber_active) {
    const Rows v_rows = s * grad_aca + aca * s_j * grad_j;
    const auto v = flat<N>(v_rows);
    H.noalias() += psi * v * v.transpose();
  }
  // d^2J/dQ_i dQ_j = -[w]x with w = F (D_i x D_j): the current edge opposite to i and j over
  // 6 V0, as in eq. 8.
  const double scale_hj = through_j * s_j + volumetric.d1;
  const double diagonal_t = mu * s;
  const double diagonal_a = 2.0 * phi * s;
  for (int i = 0; i < N; ++i) {
    for (int j = i; j < N; ++j) {
      const double diagonal =
          diagonal_t * D.row(i).dot(D.row(j)) + diagonal_a * a_dot_d(i) * a_dot_d(j);
      for (int a = 0; a < 3; ++a)
        H(3 * i + a, 3 * j + a) += diagonal;
      if (j == i)
        continue;
      for (int a = 0; a < 3; ++a)
        H(3 * j + a, 3 * i + a) += diagonal;
      // Block (i, j) += [w]x^T, block (j, i) += [w]x.
      const Eigen::Vector3d w = scale_hj * (F * D.row(i).transpose().cross(D.row(j).transpose()));
      H(3 * i, 3 * j + 1) += w(2);
      H(3 * i, 3 * j + 2) -= w(1);
      H(3 * i + 1, 3 * j) -= w(2);
      H(3 * i + 1, 3 * j + 2) += w(0);
      H(3 * i + 2, 3 * j) += w(1);
      H(3 * i + 2, 3 * j + 1) -= w(0);
      H(3 * j + 1, 3 * i) += w(2);
      H(3 * j + 2, 3 * i) -= w(1);
      H(3 * j, 3 * i + 1) -= w(2);
      H(3 * j + 2, 3 * i + 1) += w(0);
      H(3 * j, 3 * i + 2) += w(1);
      H(3 * j + 1, 3 * i + 2) -= w(0);
    }
  }
  H *= V0;
}

WeissMaterial::PointState WeissMaterial::state_at(const Eigen::Matrix3d& F,
                                                  const Eigen::Vector3d& fiber) const
{
  PointState state;
  state.J = F.determinant();
  state.inverted = !(state.J > 0.0) || !std::isfinite(state.J);
  if (state.inverted)
    return state;
  const double mu = m_parameters.mu_mpa;
  state.trace_c = F.squaredNorm(); // tr C (eq. 3)
  state.s = std::pow(state.J, -2.0 / 3.0);
  const double i1 = state.s * state.trace_c; // eq. 6
  state.volumetric =
      volumetric_response(m_parameters.volumetric, m_parameters.bulk_modulus_mpa, state.J);
  // Fiber family (eq. 6, 14-21): I4 = J^-2/3 aCa = lambda^2.
  if (m_fiber_law) {
    state.fa = F * fiber;
    state.aca = state.fa.squaredNorm();
    state.lambda = std::sqrt(state.s * state.aca);
    state.fiber_response = m_fiber_law->evaluate(state.lambda);
  }
  state.energy_density =
      0.5 * mu * (i1 - 3.0) + state.fiber_response.energy + state.volumetric.energy;
  return state;
}

template void WeissMaterial::evaluate_at_point<4>(const NodeRows<4>&, const NodeRows<4>&, double,
                                                  const Eigen::Vector3d&, ElementNeeds,
                                                  NodalEvaluation<4>&) const;
template void WeissMaterial::evaluate_at_point<10>(const NodeRows<10>&, const NodeRows<10>&, double,
                                                   const Eigen::Vector3d&, ElementNeeds,
                                                   NodalEvaluation<10>&) const;

ElementMeasures WeissMaterial::measures(const TetCorners& Q, const TetShape& shape,
                                        const Eigen::Vector3d& fiber) const
{
  return measures_at(Q.transpose() * shape.D, fiber);
}

ElementMeasures WeissMaterial::measures_at(const Eigen::Matrix3d& F,
                                           const Eigen::Vector3d& fiber) const
{
  const PointState state = state_at(F, fiber);
  ElementMeasures result;
  result.J = state.J;
  if (state.inverted)
    return result;
  result.energy_density_mpa = state.energy_density;
  if (m_fiber_law) {
    result.deformed_fiber = F * fiber;
    result.fiber_stretch = result.deformed_fiber.norm();
    result.deviatoric_fiber_stretch = std::pow(state.J, -1.0 / 3.0) * result.fiber_stretch;
  }
  return result;
}

template <int Size> bool project_to_psd(Eigen::Matrix<double, Size, Size>& H)
{
  // An element's energy is unchanged by a translation, so its Hessian is H = P^T G P with G the
  // block of all nodes but the first (their motion relative to it; P is onto), and H is
  // positive semi-definite where G is positive definite: a Cholesky of that block settles
  // those elements without the eigen-decomposition of H (4.5 % of a free knee sweep's time
  // with linear tets). Any other matrix goes to the decomposition.
  constexpr int rest = Size - 3;
  Eigen::Matrix<double, Size, 3> translated = Eigen::Matrix<double, Size, 3>::Zero();
  for (int node = 0; node < Size / 3; ++node)
    translated += H.template middleCols<3>(3 * node);
  if (translated.cwiseAbs().maxCoeff() <= 1e-12 * H.cwiseAbs().maxCoeff() &&
      Eigen::LLT<Eigen::Matrix<double, rest, rest>>(H.template bottomRightCorner<rest, rest>())
              .info() == Eigen::Success)
    return false;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, Size, Size>> eigen(H);
  const auto& values = eigen.eigenvalues();
  if (values.minCoeff() >= 0.0)
    return false;
  // A linear tet's negative eigenvalues are clamped to zero. A 10-node tet's are mirrored to their
  // absolute values (Chen et al., "Trust-region eigenvalue filtering for projected Newton",
  // SIGGRAPH Asia 2024): clamped, nearly every element of a slack band loses those directions,
  // and the Newton steps along them run into inversions. On the female HRA MCL of 10-node tets
  // (1.8 mm), flexion to 30 degrees without contact took 128 Newton iterations against 253, and
  // the sweep to 120 with contact 65 s against 210 s, its forces equal to 4 digits.
  const Eigen::Matrix<double, Size, 1> filtered =
      Size == 30 ? Eigen::Matrix<double, Size, 1>(values.cwiseAbs())
                 : Eigen::Matrix<double, Size, 1>(values.cwiseMax(0.0));
  H.noalias() = eigen.eigenvectors() * filtered.asDiagonal() * eigen.eigenvectors().transpose();
  return true;
}

template bool project_to_psd<12>(Eigen::Matrix<double, 12, 12>&);
template bool project_to_psd<30>(Eigen::Matrix<double, 30, 30>&);

} // namespace ligsim::sim
