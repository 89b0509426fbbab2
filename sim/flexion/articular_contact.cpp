#include "sim/flexion/articular_contact.hpp"

#include "common/error.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace ligsim::sim {

std::optional<ArticularProblem> articular_problem(const ArticularSettings& s)
{
  if (!(s.modulus_mpa > 0.0) || !std::isfinite(s.modulus_mpa))
    return ArticularProblem{"modulus_mpa", fmt::format("must be positive, got {}", s.modulus_mpa)};
  if (!(s.poisson >= 0.0 && s.poisson < 0.5))
    return ArticularProblem{"poisson", fmt::format("must be in [0, 0.5), got {}", s.poisson)};
  if (!(s.thickness_mm > 0.0) || !std::isfinite(s.thickness_mm))
    return ArticularProblem{"thickness_mm",
                            fmt::format("must be positive, got {}", s.thickness_mm)};
  if (!std::isfinite(s.gap_mm) || s.gap_mm < 0.0)
    return ArticularProblem{"gap_mm", fmt::format("must be zero or positive, got {}", s.gap_mm)};
  return std::nullopt;
}

void validate(const ArticularSettings& s)
{
  if (const auto problem = articular_problem(s))
    fail("[articular] {} {}", problem->key, problem->what);
}

ArticularContact::ArticularContact(const TriangleSurface& femur, const DistanceField& tibia,
                                   const JointCoordinateSystem& jcs,
                                   const ArticularSettings& settings)
    : m_tibia(tibia)
    , m_jcs(jcs)
    , m_settings(settings)
{
  validate(settings);
  const double nu = settings.poisson;
  m_stiffness =
      (1.0 - nu) * settings.modulus_mpa / ((1.0 + nu) * (1.0 - 2.0 * nu)) / settings.thickness_mm;
  // The condyles: the femur within 60 mm of the knee's centre (the rest lies far from any tibia).
  const Eigen::Vector3d e1 = joint_axes(jcs).col(0);
  const double side = jcs.side >= 0 ? 1.0 : -1.0;
  for (Eigen::Index f = 0; f < femur.F.rows(); ++f) {
    const Eigen::Vector3d a = femur.V.row(femur.F(f, 0)), b = femur.V.row(femur.F(f, 1)),
                          c = femur.V.row(femur.F(f, 2));
    const Eigen::Vector3d centre = (a + b + c) / 3.0;
    if ((centre - jcs.origin_mm).norm() > 60.0)
      continue;
    const bool medial = side * (centre - jcs.origin_mm).dot(e1) < 0.0;
    m_samples.push_back({centre, 0.5 * (b - a).cross(c - a).norm(), medial});
    double& built = medial ? m_seat.medial_built_mm : m_seat.lateral_built_mm;
    if (tibia.distance_bound(centre) <= kMaxSeatMm)
      built = std::min(built, tibia.sample(centre, false).distance_mm);
  }
  const auto gap = [&](double built) {
    return settings.seated && built <= kMaxSeatMm ? std::max(settings.gap_mm, built)
                                                  : settings.gap_mm;
  };
  m_seat.medial_gap_mm = gap(m_seat.medial_built_mm);
  m_seat.lateral_gap_mm = gap(m_seat.lateral_built_mm);
  for (Sample& sample : m_samples)
    sample.gap_mm = sample.medial ? m_seat.medial_gap_mm : m_seat.lateral_gap_mm;
}

ArticularState ArticularContact::evaluate(const FreePose& pose) const
{
  ArticularState state;
  double medial_weight = 0.0, lateral_weight = 0.0;
  Eigen::Vector3d medial_sum = Eigen::Vector3d::Zero(), lateral_sum = Eigen::Vector3d::Zero();
  for (const Sample& s : m_samples) {
    const Eigen::Vector3d p = pose.point(s.rest_mm);
    if (m_tibia.distance_bound(p) >= s.gap_mm)
      continue;
    const DistanceSample d = m_tibia.sample(p, true);
    const double delta = s.gap_mm - d.distance_mm;
    if (delta <= 0.0)
      continue;
    const Matrix35d J = pose.jacobian(s.rest_mm);
    const Eigen::Matrix<double, 1, 5> dd = d.gradient.transpose() * J; // d distance / d q
    const Matrix5d ddd =
        J.transpose() * d.hessian * J + pose.weighted_second(s.rest_mm, d.gradient);
    const double k = m_stiffness * s.area_mm2; // N/mm per mm of overlap
    state.energy_nmm += 0.5 * k * delta * delta;
    state.gradient -= k * delta * dd.transpose();
    state.hessian += k * (dd.transpose() * dd - delta * ddd);
    // The tibia pushes the femur out along its distance gradient.
    const Eigen::Vector3d force = k * delta * d.gradient;
    const Eigen::Vector3d on_tibia = p - d.distance_mm * d.gradient;
    state.moment_nmm += (p - m_jcs.origin_mm).cross(force);
    state.area_mm2 += s.area_mm2;
    state.max_pressure_mpa = std::max(state.max_pressure_mpa, m_stiffness * delta);
    const bool medial = s.medial;
    (medial ? state.medial_force_n : state.lateral_force_n) += force;
    (medial ? medial_sum : lateral_sum) += force.norm() * on_tibia;
    (medial ? medial_weight : lateral_weight) += force.norm();
  }
  if (medial_weight > 0.0)
    state.medial_centre_mm = medial_sum / medial_weight;
  if (lateral_weight > 0.0)
    state.lateral_centre_mm = lateral_sum / lateral_weight;
  state.hessian = 0.5 * (state.hessian + state.hessian.transpose()).eval();
  return state;
}

} // namespace ligsim::sim
