#include "sim/flexion/axis/condyle_axis.hpp"

#include "common/error.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <unsupported/Eigen/LevenbergMarquardt>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace ligsim::sim {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDistalWindowMm = 50.0;   // the condyles: 2 radii above the distal-most point
constexpr double kMinFromDistalDeg = 15.0; // normal's sagittal angle from distal toward posterior
constexpr double kMaxFromDistalDeg = 165.0;
constexpr double kMaxOutOfPlaneDeg = 45.0; // normal's angle out of the sagittal plane
constexpr double kTrimSigmas = 2.5;        // kept: |residual| <= this many robust sigmas
constexpr double kRobustSigmaPerMedian = 1.4826;
constexpr double kMaxTurnDeg = 45.0;       // fitted axis against proximal x posterior
constexpr double kMaxRadiusPerSize = 10.0; // radius against the candidates' extent
constexpr int kMinPoints = 12;
constexpr int kMaxTrimRounds = 30;
constexpr int kMaxLmEvaluations = 400;

double deg(double radians)
{
  return radians * 180.0 / kPi;
}
double rad(double degrees)
{
  return degrees * kPi / 180.0;
}

/// Orthonormal frame from the hints: proximal, posterior (made perpendicular), and
/// flexion = proximal x posterior, the first guess of the axis.
struct HintFrame {
  Eigen::Vector3d proximal, posterior, flexion;
};

HintFrame hint_frame(const Eigen::Vector3d& proximal, const Eigen::Vector3d& posterior)
{
  if (!proximal.allFinite() || !posterior.allFinite())
    fail("flexion axis: the proximal ({}, {}, {}) and posterior ({}, {}, {}) hints must be "
         "finite",
         proximal.x(), proximal.y(), proximal.z(), posterior.x(), posterior.y(), posterior.z());
  if (proximal.norm() == 0.0 || posterior.norm() == 0.0)
    fail("flexion axis: the {} hint is the zero vector",
         proximal.norm() == 0.0 ? "proximal" : "posterior");
  HintFrame frame;
  frame.proximal = proximal.normalized();
  const Eigen::Vector3d across = posterior - posterior.dot(frame.proximal) * frame.proximal;
  // Closer than 10 degrees to parallel leaves no usable sagittal plane.
  if (across.norm() < std::sin(rad(10.0)) * posterior.norm())
    fail("flexion axis: the posterior hint is (nearly) parallel to the proximal one ({:.1f} "
         "degrees apart)",
         deg(std::acos(std::clamp(posterior.normalized().dot(frame.proximal), -1.0, 1.0))));
  frame.posterior = across.normalized();
  frame.flexion = frame.proximal.cross(frame.posterior);
  return frame;
}

/// Outward unit vertex normals (#V x 3; zero rows for vertices of no face), area-weighted from
/// the faces; the orientation is flipped when the signed volume is negative.
Points outward_vertex_normals(const TriangleSurface& surface)
{
  const Eigen::Index vertex_count = surface.V.rows();
  for (Eigen::Index v = 0; v < vertex_count; ++v)
    if (!surface.V.row(v).allFinite())
      fail("flexion axis: femur vertex {} has a non-finite coordinate ({}, {}, {})", v,
           surface.V(v, 0), surface.V(v, 1), surface.V(v, 2));
  Points normals = Points::Zero(vertex_count, 3);
  double volume = 0.0;
  const Eigen::RowVector3d origin =
      vertex_count > 0 ? Eigen::RowVector3d(surface.V.colwise().mean()) : Eigen::RowVector3d();
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f) {
    for (int k = 0; k < 3; ++k)
      if (surface.F(f, k) < 0 || surface.F(f, k) >= vertex_count)
        fail("flexion axis: femur face {} refers to vertex {}, but the surface has {} vertices", f,
             surface.F(f, k), vertex_count);
    const Eigen::Vector3d a = (surface.V.row(surface.F(f, 0)) - origin).transpose();
    const Eigen::Vector3d b = (surface.V.row(surface.F(f, 1)) - origin).transpose();
    const Eigen::Vector3d c = (surface.V.row(surface.F(f, 2)) - origin).transpose();
    const Eigen::Vector3d area_normal = (b - a).cross(c - a); // twice the area
    volume += a.dot(b.cross(c)) / 6.0;
    for (int k = 0; k < 3; ++k)
      normals.row(surface.F(f, k)) += area_normal.transpose();
  }
  if (volume < 0.0)
    normals = -normals;
  for (Eigen::Index v = 0; v < vertex_count; ++v) {
    const double length = normals.row(v).norm();
    if (length > 0.0)
      normals.row(v) /= length;
  }
  return normals;
}

/// A cylinder in coordinates relative to the candidates' centroid: `point` on the axis and
/// perpendicular to it, `axis` unit.
struct Cylinder {
  Eigen::Vector3d point, axis;
  double radius = 0.0;
};

/// Two unit vectors completing `axis` to an orthonormal frame.
void complete_frame(const Eigen::Vector3d& axis, Eigen::Vector3d& u, Eigen::Vector3d& v)
{
  u = axis.unitOrthogonal();
  v = axis.cross(u);
}

/// Signed distances of the points (rows, relative coordinates) to the cylinder surface.
Eigen::VectorXd cylinder_residuals(const Points& Q, const Cylinder& cylinder)
{
  Eigen::VectorXd d(Q.rows());
  for (Eigen::Index i = 0; i < Q.rows(); ++i) {
    const Eigen::Vector3d w = Q.row(i).transpose() - cylinder.point;
    d(i) = (w - w.dot(cylinder.axis) * cylinder.axis).norm() - cylinder.radius;
  }
  return d;
}

/// The kept points' distances to a cylinder, for MINPACK's Levenberg-Marquardt (Eigen's port).
/// Parameters: the start axis a0 turned by (alpha, beta) along the frame (u, v) perpendicular to
/// it, axis = (a0 + alpha u + beta v) / |.|, the start point moved by (s, t) along (u, v), the
/// radius. The fit turns the axis by a few degrees at most, far from the parametrisation's pole.
class CylinderDistances : public Eigen::DenseFunctor<double> {
public:
  CylinderDistances(const Points& Q, const std::vector<Eigen::Index>& rows, const Cylinder& start)
      : Eigen::DenseFunctor<double>(5, static_cast<int>(rows.size()))
      , m_Q(Q)
      , m_rows(rows)
      , m_start(start)
  {
    complete_frame(start.axis, m_u, m_v);
  }

  Cylinder cylinder(const InputType& x) const
  {
    Cylinder c;
    c.axis = (m_start.axis + x(0) * m_u + x(1) * m_v).normalized();
    c.point = m_start.point + x(2) * m_u + x(3) * m_v; // on the axis, not yet perpendicular
    c.radius = m_start.radius + x(4);
    return c;
  }

  int operator()(const InputType& x, ValueType& distances) const
  {
    const Cylinder c = cylinder(x);
    for (std::size_t k = 0; k < m_rows.size(); ++k)
      distances(static_cast<Eigen::Index>(k)) = radial(c, k).norm() - c.radius;
    return 0;
  }

  int df(const InputType& x, JacobianType& jacobian) const
  {
    const Cylinder c = cylinder(x);
    const Eigen::Vector3d n = m_start.axis + x(0) * m_u + x(1) * m_v;
    // d axis / d alpha: u's part perpendicular to the axis over |n|; likewise for beta.
    const Eigen::Vector3d du = (m_u - c.axis.dot(m_u) * c.axis) / n.norm();
    const Eigen::Vector3d dv = (m_v - c.axis.dot(m_v) * c.axis) / n.norm();
    for (std::size_t k = 0; k < m_rows.size(); ++k) {
      const Eigen::Vector3d r = radial(c, k);
      const double distance = r.norm();
      const auto row = static_cast<Eigen::Index>(k);
      if (distance == 0.0) { // on the axis: no defined derivative, and far from any sensible fit
        jacobian.row(row).setZero();
        continue;
      }
      const Eigen::Vector3d e = r / distance;
      const double along = (m_Q.row(m_rows[k]).transpose() - c.point).dot(c.axis);
      // d distance / d axis = -along e; d distance / d point = -e (both along e's direction).
      jacobian.row(row) << -along * e.dot(du), -along * e.dot(dv), -e.dot(m_u), -e.dot(m_v), -1.0;
    }
    return 0;
  }

private:
  /// Point k's offset from the axis, perpendicular to it.
  Eigen::Vector3d radial(const Cylinder& c, std::size_t k) const
  {
    const Eigen::Vector3d w = m_Q.row(m_rows[k]).transpose() - c.point;
    return w - w.dot(c.axis) * c.axis;
  }

  const Points& m_Q;
  const std::vector<Eigen::Index>& m_rows;
  Cylinder m_start;
  Eigen::Vector3d m_u, m_v;
};

/// The geometric least-squares cylinder through the points flagged in `kept`, from `cylinder`.
/// False when MINPACK's Levenberg-Marquardt gives up (out of evaluations, or bad input); its
/// stops at round-off (no further reduction possible) count as converged.
bool fit_cylinder(const Points& Q, const std::vector<char>& kept, Cylinder& cylinder,
                  int& iterations)
{
  std::vector<Eigen::Index> rows;
  for (Eigen::Index i = 0; i < Q.rows(); ++i)
    if (kept[static_cast<std::size_t>(i)])
      rows.push_back(i);
  CylinderDistances distances(Q, rows, cylinder);
  Eigen::LevenbergMarquardt<CylinderDistances> lm(distances);
  lm.setXtol(1e-12);
  lm.setFtol(1e-15);
  lm.setMaxfev(kMaxLmEvaluations);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(5);
  const Eigen::LevenbergMarquardtSpace::Status status = lm.minimize(x);
  iterations += static_cast<int>(lm.njev()); // one Jacobian per iteration
  if (!x.allFinite())
    return false;
  cylinder = distances.cylinder(x);
  cylinder.point -= cylinder.point.dot(cylinder.axis) * cylinder.axis;
  return status != Eigen::LevenbergMarquardtSpace::ImproperInputParameters &&
         status != Eigen::LevenbergMarquardtSpace::TooManyFunctionEvaluation;
}

double median(std::vector<double> values)
{
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

} // namespace

CondyleAxisFit fit_condyle_axis(const TriangleSurface& femur, const Eigen::Vector3d& proximal,
                                const Eigen::Vector3d& posterior)
{
  const HintFrame frame = hint_frame(proximal, posterior);
  const Points normals = outward_vertex_normals(femur);
  const Eigen::Index vertex_count = femur.V.rows();

  // Candidates: distal slab, posterior half of it, normal between distal and posterior.
  std::vector<Eigen::Index> slab;
  double lowest = INFINITY;
  for (Eigen::Index i = 0; i < vertex_count; ++i)
    if (normals.row(i).squaredNorm() > 0.0)
      lowest = std::min(lowest, femur.V.row(i).dot(frame.proximal));
  double back_min = INFINITY, back_max = -INFINITY;
  for (Eigen::Index i = 0; i < vertex_count; ++i) {
    if (normals.row(i).squaredNorm() == 0.0 ||
        femur.V.row(i).dot(frame.proximal) > lowest + kDistalWindowMm)
      continue;
    slab.push_back(i);
    back_min = std::min(back_min, femur.V.row(i).dot(frame.posterior));
    back_max = std::max(back_max, femur.V.row(i).dot(frame.posterior));
  }
  const double back_middle = 0.5 * (back_min + back_max);
  std::vector<Eigen::Index> candidates;
  for (const Eigen::Index i : slab) {
    const Eigen::Vector3d n = normals.row(i).transpose();
    const double from_distal = deg(std::atan2(n.dot(frame.posterior), -n.dot(frame.proximal)));
    if (femur.V.row(i).dot(frame.posterior) >= back_middle &&
        std::abs(n.dot(frame.flexion)) <= std::sin(rad(kMaxOutOfPlaneDeg)) &&
        from_distal >= kMinFromDistalDeg && from_distal <= kMaxFromDistalDeg)
      candidates.push_back(i);
  }
  const int candidate_count = static_cast<int>(candidates.size());
  if (candidate_count < kMinPoints)
    fail("flexion axis: only {} posterior-facing vertices on the femur surface ({} vertices, {} "
         "faces); need at least {}",
         candidate_count, vertex_count, femur.F.rows(), kMinPoints);

  // Relative coordinates and the sagittal frame of the first guess.
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Index i : candidates)
    centroid += femur.V.row(i).transpose();
  centroid /= candidate_count;
  Points Q(candidate_count, 3), M(candidate_count, 3);
  for (int k = 0; k < candidate_count; ++k) {
    Q.row(k) = femur.V.row(candidates[static_cast<std::size_t>(k)]) - centroid.transpose();
    M.row(k) = normals.row(candidates[static_cast<std::size_t>(k)]);
  }
  const double length_scale = std::max((Q.colwise().maxCoeff() - Q.colwise().minCoeff()).norm(),
                                       std::numeric_limits<double>::min());
  const double residual_floor = 1e-9 * length_scale;

  // First guess from the normals: p_i - r n_i = centre in the sagittal plane, trimmed.
  const Eigen::Vector3d su = frame.posterior, sv = frame.proximal;
  std::vector<char> kept(static_cast<std::size_t>(candidate_count), 1);
  Eigen::Vector3d start = Eigen::Vector3d::Zero(); // centre (along su, sv) and radius
  for (int round = 0; round < kMaxTrimRounds; ++round) {
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    for (int k = 0; k < candidate_count; ++k) {
      if (!kept[static_cast<std::size_t>(k)])
        continue;
      const Eigen::Vector2d m = Eigen::Vector2d(M.row(k).dot(su), M.row(k).dot(sv)).normalized();
      const Eigen::Vector2d q(Q.row(k).dot(su), Q.row(k).dot(sv));
      Eigen::Matrix<double, 2, 3> rows;
      rows << 1.0, 0.0, m.x(), 0.0, 1.0, m.y();
      A += rows.transpose() * rows;
      b += rows.transpose() * q;
    }
    start = A.ldlt().solve(b);
    std::vector<double> misses(static_cast<std::size_t>(candidate_count));
    std::vector<double> kept_misses;
    for (int k = 0; k < candidate_count; ++k) {
      const Eigen::Vector2d m = Eigen::Vector2d(M.row(k).dot(su), M.row(k).dot(sv)).normalized();
      const Eigen::Vector2d q(Q.row(k).dot(su), Q.row(k).dot(sv));
      misses[static_cast<std::size_t>(k)] = (q - start(2) * m - start.head<2>()).norm();
      if (kept[static_cast<std::size_t>(k)])
        kept_misses.push_back(misses[static_cast<std::size_t>(k)]);
    }
    const double bound =
        std::max(kTrimSigmas * kRobustSigmaPerMedian * median(kept_misses), residual_floor);
    std::vector<char> next(kept.size());
    for (std::size_t k = 0; k < next.size(); ++k)
      next[k] = misses[k] <= bound;
    if (next == kept || std::count(next.begin(), next.end(), 1) < kMinPoints)
      break;
    kept = next;
  }
  if (!start.allFinite() || start(2) <= 0.0)
    fail("flexion axis: the posterior femur surface is not convex like a condyle (first guess of "
         "the radius {:.3g} mm from {} vertices)",
         start(2), candidate_count);

  Cylinder cylinder;
  cylinder.axis = frame.flexion;
  cylinder.point = start(0) * su + start(1) * sv;
  cylinder.radius = start(2);

  // Geometric fit, alternating with trimming until the kept set is stable.
  CondyleAxisFit fit;
  fit.points_considered = candidate_count;
  Eigen::VectorXd residuals;
  for (int round = 0; round < kMaxTrimRounds; ++round) {
    if (std::count(kept.begin(), kept.end(), 1) < kMinPoints)
      fail("flexion axis: only {} of {} posterior-facing vertices lie on a common cylinder; "
           "need at least {}",
           std::count(kept.begin(), kept.end(), 1), candidate_count, kMinPoints);
    ++fit.trimming_rounds;
    const bool converged = fit_cylinder(Q, kept, cylinder, fit.iterations);
    if (!(cylinder.radius < kMaxRadiusPerSize * length_scale))
      fail("flexion axis: the posterior femur surface is too flat for a condyle (the cylinder "
           "radius grew past {:.3g} mm on {} vertices)",
           kMaxRadiusPerSize * length_scale, candidate_count);
    if (!converged)
      fail("flexion axis: the cylinder fit to {} posterior condyle vertices did not converge in "
           "{} evaluations",
           std::count(kept.begin(), kept.end(), 1), kMaxLmEvaluations);
    if (!(cylinder.radius > 0.0) || !cylinder.point.allFinite() || !cylinder.axis.allFinite())
      fail("flexion axis: the cylinder fit to the posterior condyles degenerated (radius {:.3g} "
           "mm)",
           cylinder.radius);
    residuals = cylinder_residuals(Q, cylinder);
    std::vector<double> kept_residuals;
    for (int k = 0; k < candidate_count; ++k)
      if (kept[static_cast<std::size_t>(k)])
        kept_residuals.push_back(std::abs(residuals(k)));
    const double bound =
        std::max(kTrimSigmas * kRobustSigmaPerMedian * median(kept_residuals), residual_floor);
    std::vector<char> next(kept.size());
    for (std::size_t k = 0; k < next.size(); ++k)
      next[k] = std::abs(residuals(static_cast<Eigen::Index>(k))) <= bound;
    if (next == kept || round + 1 == kMaxTrimRounds)
      break; // the kept set stays the one the cylinder was fitted to
    kept = next;
  }

  // Orientation, and sanity against the hints.
  if (cylinder.axis.dot(frame.flexion) < 0.0)
    cylinder.axis = -cylinder.axis;
  const double turn = deg(std::acos(std::clamp(cylinder.axis.dot(frame.flexion), -1.0, 1.0)));
  if (turn > kMaxTurnDeg)
    fail("flexion axis: the fitted cylinder axis is {:.1f} degrees from proximal x posterior "
         "(at most {:.0f} expected); check the proximal and posterior hints",
         turn, kMaxTurnDeg);

  double sum_squares = 0.0, along_min = INFINITY, along_max = -INFINITY;
  for (int k = 0; k < candidate_count; ++k) {
    if (!kept[static_cast<std::size_t>(k)])
      continue;
    ++fit.points_used;
    fit.used_vertices.push_back(static_cast<int>(candidates[static_cast<std::size_t>(k)]));
    sum_squares += residuals(k) * residuals(k);
    const double along = (Q.row(k).transpose() - cylinder.point).dot(cylinder.axis);
    along_min = std::min(along_min, along);
    along_max = std::max(along_max, along);
  }
  fit.rms_residual_mm = std::sqrt(sum_squares / fit.points_used);
  fit.radius_mm = cylinder.radius;
  fit.span_mm = along_max - along_min;
  fit.axis.direction = cylinder.axis;
  fit.axis.point_mm = centroid + cylinder.point + 0.5 * (along_min + along_max) * cylinder.axis;
  return fit;
}

} // namespace ligsim::sim
