#include "sim/solver/arc_length.hpp"

#include "common/error.hpp"

#include <Eigen/SparseCholesky>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace ligsim::sim {

namespace {

/// The tangent factorised as L D L^T without pivoting (indefinite matrices factorise unless a
/// pivot is zero); D's negative entries count the negative eigenvalues (Sylvester).
class Tangent {
public:
  bool factorize(const EquilibriumSystem& system, const Eigen::VectorXd& u)
  {
    system.tangent(u, m_matrix);
    if (!m_analyzed) {
      m_ldlt.analyzePattern(m_matrix);
      m_analyzed = true;
    }
    m_ldlt.factorize(m_matrix);
    return m_ldlt.info() == Eigen::Success && m_ldlt.vectorD().allFinite() &&
           (m_ldlt.vectorD().array() != 0.0).all();
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const { return m_ldlt.solve(b); }
  int negative_eigenvalues() const
  {
    return static_cast<int>((m_ldlt.vectorD().array() < 0.0).count());
  }

private:
  Eigen::SparseMatrix<double> m_matrix;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> m_ldlt;
  bool m_analyzed = false;
};

/// The plane w du_p . du + dlambda_p dlambda = 0 normal to the predictor (du_p, dlambda_p) in
/// the scaled arc's metric: Riks' corrector stays on it.
struct NormalPlane {
  const Eigen::VectorXd& du_p;
  double dlambda_p = 0.0;
  double w = 0.0;
};

/// Newton's corrector from (u, lambda): on the normal plane (bordered solves) or, without one, at
/// the fixed load factor lambda. False when it does not converge; `iterations` counts its solves.
bool correct(const EquilibriumSystem& system, Tangent& tangent, const NormalPlane* plane,
             const ArcLengthSettings& settings, Eigen::VectorXd& u, double& lambda, int& iterations)
{
  const Eigen::VectorXd& f = system.load();
  const double tolerance = settings.residual_tolerance * f.norm();
  Eigen::VectorXd g;
  for (iterations = 0;; ++iterations) {
    if (!system.internal_force(u, g))
      return false;
    const Eigen::VectorXd residual = g - lambda * f;
    if (!residual.allFinite())
      return false;
    if (residual.norm() <= tolerance)
      return true;
    if (iterations == settings.max_iterations || !tangent.factorize(system, u))
      return false;
    Eigen::VectorXd du = tangent.solve(-residual);
    if (plane) {
      const Eigen::VectorXd b = tangent.solve(f);
      const double dlambda =
          -plane->w * plane->du_p.dot(du) / (plane->w * plane->du_p.dot(b) + plane->dlambda_p);
      du += dlambda * b;
      lambda += dlambda;
    }
    u += du;
  }
}

/// The extremum of the parabola through (s_i, lambda_i), i = 0, 1, 2.
double parabola_extremum(const PathPoint& a, const PathPoint& b, const PathPoint& c)
{
  const double d1 = (b.load_factor - a.load_factor) / (b.arc - a.arc);
  const double d2 = (c.load_factor - b.load_factor) / (c.arc - b.arc);
  const double curvature = (d2 - d1) / (c.arc - a.arc); // lambda = p + q s + curvature s^2
  if (curvature == 0.0)
    return b.load_factor;
  const double slope_at_b = d1 + curvature * (b.arc - a.arc);
  return b.load_factor - slope_at_b * slope_at_b / (4.0 * curvature);
}

/// Whether the load factor turns at path point i (0 < i < size - 1).
bool turns_at(const std::vector<PathPoint>& path, std::size_t i)
{
  return i > 0 && i + 1 < path.size() &&
         (path[i].load_factor - path[i - 1].load_factor) *
                 (path[i + 1].load_factor - path[i].load_factor) <
             0.0;
}

/// The load factor turning at point i: a limit point, at the parabola's extremum.
CriticalPoint limit_point(const std::vector<PathPoint>& path, std::size_t i)
{
  return {"limit point", parabola_extremum(path[i - 1], path[i], path[i + 1]),
          path[i - 1].load_factor, path[i + 1].load_factor, static_cast<int>(i)};
}

/// The inertia changing between points i and i + 1 where the load factor turns at neither
/// (once the point after i + 1 exists, or i + 1 is the last).
bool bifurcation_between(const std::vector<PathPoint>& path, std::size_t i)
{
  return i + 1 < path.size() && path[i].negative_eigenvalues != path[i + 1].negative_eigenvalues &&
         !turns_at(path, i) && !turns_at(path, i + 1);
}

CriticalPoint bifurcation(const std::vector<PathPoint>& path, std::size_t i)
{
  return {"bifurcation", 0.5 * (path[i].load_factor + path[i + 1].load_factor), path[i].load_factor,
          path[i + 1].load_factor, static_cast<int>(i + 1)};
}

} // namespace

BodyEquilibrium::BodyEquilibrium(const HyperelasticBody& body, const BoundaryConditions& conditions)
    : m_body(body)
    , m_dofs(body.node_count(), conditions, body.unreferenced_nodes())
    , m_rest(body.rest_positions())
    , m_stiffness(body.elements(), m_dofs)
{
  if (m_dofs.has_moving_targets())
    fail("arc-length continuation: a prescribed displacement or rigid motion moves with the "
         "load factor; it follows dead nodal loads on fixed supports only");
  if (m_dofs.free_count() == 0)
    fail("every degree of freedom is prescribed: nothing to solve");
  const Eigen::VectorXd external = m_dofs.external_forces(conditions);
  m_load = m_dofs.gather(external);
}

Eigen::VectorXd BodyEquilibrium::rest_unknowns() const
{
  return m_dofs.gather(m_rest);
}

Eigen::VectorXd BodyEquilibrium::positions(const Eigen::VectorXd& u) const
{
  Eigen::VectorXd x = m_rest;
  m_dofs.scatter(u, x);
  return x;
}

bool BodyEquilibrium::internal_force(const Eigen::VectorXd& u, Eigen::VectorXd& g) const
{
  Eigen::VectorXd gradient;
  if (!std::isfinite(m_body.energy_gradient(positions(u), gradient).energy))
    return false;
  g = m_dofs.gather(gradient);
  return true;
}

void BodyEquilibrium::tangent(const Eigen::VectorXd& u, Eigen::SparseMatrix<double>& K) const
{
  const Eigen::VectorXd x = positions(u);
  m_stiffness.set_zero();
  m_stiffness.add_elements(m_body, x, false);
  K = m_stiffness.matrix();
}

ArcLengthResult follow_path(const EquilibriumSystem& system, Eigen::VectorXd& u,
                            const ArcLengthSettings& settings)
{
  ArcLengthResult result;
  const Eigen::VectorXd& f = system.load();
  const double target = settings.target_load_factor;
  Tangent tangent;
  if (u.size() != system.size() || !u.allFinite() || f.norm() == 0.0 ||
      !tangent.factorize(system, u)) {
    result.failure = "the start is not an admissible state with a regular tangent and a load";
    return result;
  }
  // Scaled arc: ds^2 = w |du|^2 + dlambda^2, w = 1 / |K0^-1 f|^2, so that at the start a unit
  // load factor and the displacement it causes weigh the same.
  const Eigen::VectorXd v0 = tangent.solve(f);
  const double w = 1.0 / v0.squaredNorm();
  const double first_arc = std::sqrt(2.0) * settings.first_load_increment;
  double arc = first_arc;
  double lambda = 0.0;
  Eigen::VectorXd previous_du = Eigen::VectorXd::Zero(u.size());
  double previous_dlambda = 0.0;
  result.path.push_back({0.0, 0.0, tangent.negative_eigenvalues(), 0});

  bool regular = true; // the tangent at u is factorised and regular
  for (int step = 1; step <= settings.max_steps; ++step) {
    if (!regular) {
      result.failure =
          fmt::format("step {}: the tangent is singular at load factor {:.6g}", step, lambda);
      return result;
    }
    const Eigen::VectorXd v = tangent.solve(f);
    // The predictor keeps the direction of travel: its tangent (v, 1) points along the last
    // increment (so the load factor falls after a maximum).
    const double sign = step == 1 || w * v.dot(previous_du) + previous_dlambda >= 0.0 ? 1.0 : -1.0;
    bool converged = false;
    Eigen::VectorXd u_new;
    double lambda_new = 0.0;
    int iterations = 0;
    while (!converged) {
      const double dlambda_p = sign * arc / std::sqrt(w * v.squaredNorm() + 1.0);
      const Eigen::VectorXd du_p = dlambda_p * v;
      u_new = u + du_p;
      lambda_new = lambda + dlambda_p;
      const NormalPlane plane{du_p, dlambda_p, w};
      converged = correct(system, tangent, &plane, settings, u_new, lambda_new, iterations);
      result.newton_iterations += iterations;
      if (converged)
        break;
      ++result.cutbacks;
      arc *= 0.5;
      if (arc < settings.min_arc_fraction * first_arc) {
        result.failure = fmt::format("step {}: no equilibrium found at load factor {:.6g} with an "
                                     "arc of {:.3g} (the first was {:.3g})",
                                     step, lambda, arc, first_arc);
        return result;
      }
    }
    previous_du = u_new - u;
    previous_dlambda = lambda_new - lambda;
    const double chord =
        std::sqrt(w * previous_du.squaredNorm() + previous_dlambda * previous_dlambda);
    const Eigen::VectorXd u_old = u;
    const double lambda_old = lambda;
    u = u_new;
    lambda = lambda_new;
    regular = tangent.factorize(system, u); // for the inertia here and the next predictor
    result.path.push_back(
        {lambda, result.path.back().arc + chord, tangent.negative_eigenvalues(), iterations});

    const std::size_t n = result.path.size();
    if (n >= 3 && turns_at(result.path, n - 2))
      result.critical_points.push_back(limit_point(result.path, n - 2));
    if (n >= 3 && bifurcation_between(result.path, n - 3))
      result.critical_points.push_back(bifurcation(result.path, n - 3));

    if ((lambda_old - target) * (lambda - target) <= 0.0) {
      // The path crossed the target: Newton at the target from the chord's interpolation.
      const double s = (target - lambda_old) / (lambda - lambda_old);
      Eigen::VectorXd at_target = u_old + s * (u - u_old);
      double at_load = target;
      int newton = 0;
      const bool found = correct(system, tangent, nullptr, settings, at_target, at_load, newton);
      result.newton_iterations += newton;
      if (found) {
        u = at_target;
        result.reached = true;
        // The target replaces the point beyond it: the last segment is checked too.
        tangent.factorize(system, u);
        const double to_target = std::sqrt(w * (u - u_old).squaredNorm() +
                                           (target - lambda_old) * (target - lambda_old));
        result.path.back() = {target, result.path[n - 2].arc + to_target,
                              tangent.negative_eigenvalues(), iterations + newton};
        if (bifurcation_between(result.path, n - 2))
          result.critical_points.push_back(bifurcation(result.path, n - 2));
        return result;
      }
      result.failure = fmt::format("step {}: the path crosses load factor {:g}, but Newton "
                                   "found no equilibrium there",
                                   step, target);
      return result;
    }
    const double growth =
        std::sqrt(static_cast<double>(settings.desired_iterations) / std::max(1, iterations));
    arc = std::min(arc * std::clamp(growth, 0.5, 2.0), settings.max_arc_growth * first_arc);
  }
  result.failure = fmt::format("the path did not reach load factor {:g} in {} steps (last at "
                               "{:.6g})",
                               target, settings.max_steps, lambda);
  return result;
}

} // namespace ligsim::sim
