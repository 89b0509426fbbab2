#include "sim/flexion/free_femur.hpp"

#include "common/error.hpp"
#include "common/progress.hpp"
#include "sim/solver/parallel.hpp"

#include <Eigen/Cholesky>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

namespace ligsim::sim {

namespace {

constexpr double degree = M_PI / 180.0;
constexpr double armijo = 1e-4;
constexpr int max_line_search = 12;
constexpr std::array<const char*, 5> kCoordinate = {"varus rotation", "internal rotation",
                                                    "lateral translation", "anterior translation",
                                                    "proximal translation"};

/// The knee's state at one trial pose: what Newton needs.
struct Knee {
  std::vector<LigamentAtPose>& ligaments;
  const ArticularContact* articular;
  const JointCoordinateSystem& jcs;
  const FreeKneeSettings& settings;

  /// Every ligament's equilibrium now.
  std::vector<LigamentAtPose::Equilibrium> equilibria() const
  {
    std::vector<LigamentAtPose::Equilibrium> all;
    for (const LigamentAtPose& l : ligaments)
      all.push_back(l.equilibrium());
    return all;
  }

  void restore(const std::vector<LigamentAtPose::Equilibrium>& all)
  {
    for (std::size_t i = 0; i < ligaments.size(); ++i)
      ligaments[i].restore(all[i]);
  }

  /// Moves every ligament to (flexion, q), all at once; all or none: on a failure they are put
  /// back where they were.
  bool move(double flexion_deg, const Vector5d& q, std::string& failure)
  {
    const JointPose target = joint_pose_of(flexion_deg, q);
    const std::vector<LigamentAtPose::Equilibrium> before = equilibria();
    std::vector<char> moved(ligaments.size());
    parallel_tasks(ligaments.size(),
                   [&](std::size_t i) { moved[i] = ligaments[i].move_to(target) ? 1 : 0; });
    const auto failed = std::find(moved.begin(), moved.end(), 0);
    if (failed == moved.end())
      return true;
    failure = ligaments[static_cast<std::size_t>(failed - moved.begin())].failure();
    restore(before);
    return false;
  }

  /// The ligaments' pose stiffness at `pose`, summed in their order.
  Matrix5d stiffness(const FreePose& pose) const
  {
    std::vector<Matrix5d> each(ligaments.size());
    parallel_tasks(ligaments.size(),
                   [&](std::size_t i) { each[i] = ligaments[i].stiffness(pose); });
    Matrix5d sum = Matrix5d::Zero();
    for (const Matrix5d& k : each)
      sum += k;
    return sum;
  }

  double potential(const FreePose& pose, const Vector5d& q, ArticularState* state) const
  {
    double total = load_potential(settings.loads, q);
    for (const LigamentAtPose& l : ligaments)
      total += l.energy();
    if (articular) {
      const ArticularState a = articular->evaluate(pose);
      total += a.energy_nmm;
      if (state)
        *state = a;
    }
    return total;
  }
};

Vector5d unknown_scale(const FreeKneeSettings& settings)
{
  Vector5d s;
  s << settings.rotation_scale_mm, settings.rotation_scale_mm, 1.0, 1.0, 1.0;
  return s;
}

/// The coordinate beyond its bound, if any.
int runaway(const Vector5d& q, const FreeKneeSettings& settings)
{
  for (int k = 0; k < 5; ++k) {
    const double bound = k < 2 ? settings.max_rotation_deg * degree : settings.max_translation_mm;
    if (!std::isfinite(q(k)) || std::abs(q(k)) > bound)
      return k;
  }
  return -1;
}

std::string coordinate_value(int k, const Vector5d& q)
{
  return k < 2
             ? fmt::format("{} {:.1f} deg", kCoordinate[static_cast<std::size_t>(k)], q(k) / degree)
             : fmt::format("{} {:.1f} mm", kCoordinate[static_cast<std::size_t>(k)], q(k));
}

/// A Newton direction in the scaled unknowns: (H + lambda I) d = -g, lambda raised from 0 until
/// the matrix is positive definite (Levenberg-Marquardt), then cut to the trust region.
Vector5d newton_direction(const Matrix5d& H, const Vector5d& g, double max_step)
{
  double lambda = 0.0;
  const double floor = std::max(1e-9, 1e-6 * H.diagonal().cwiseAbs().maxCoeff());
  for (int attempt = 0; attempt < 60; ++attempt) {
    const Eigen::LDLT<Matrix5d> ldlt(H + lambda * Matrix5d::Identity());
    if (ldlt.info() == Eigen::Success && ldlt.isPositive() &&
        (ldlt.vectorD().array() > 0.0).all()) {
      Vector5d d = ldlt.solve(-g);
      if (d.allFinite() && d.dot(g) < 0.0) {
        if (d.norm() > max_step)
          d *= max_step / d.norm();
        return d;
      }
    }
    lambda = lambda == 0.0 ? floor : 4.0 * lambda;
  }
  return -g.normalized() * std::min(max_step, g.norm()); // steepest descent
}

} // namespace

double load_potential(const JointLoads& loads, const Vector5d& q)
{
  return load_gradient(loads).dot(q);
}

Vector5d load_gradient(const JointLoads& loads)
{
  // Minus the loads' work on the tibia's motion relative to the femur: a valgus moment turns the
  // tibia against varus, compression pushes it proximally (moments in N m, q in rad and mm).
  Vector5d g;
  g << 1000.0 * loads.valgus_nm, -1000.0 * loads.internal_nm, 0.0, -loads.anterior_n,
      -loads.compression_n;
  return g;
}

FreeFemurResult find_free_path(std::vector<LigamentAtPose>& ligaments,
                               const ArticularContact* articular, const JointCoordinateSystem& jcs,
                               const std::vector<double>& angles_deg,
                               const FreeKneeSettings& settings)
{
  FreeFemurResult result;
  std::vector<char> settled(ligaments.size());
  parallel_tasks(ligaments.size(),
                 [&](std::size_t i) { settled[i] = ligaments[i].settle() ? 1 : 0; });
  for (std::size_t i = 0; i < ligaments.size(); ++i)
    if (!settled[i]) {
      result.failure = "settling at the built pose: " + ligaments[i].failure();
      return result;
    }
  Knee knee{ligaments, articular, jcs, settings};
  const Vector5d scale = unknown_scale(settings);
  const double load_scale = load_gradient(settings.loads).cwiseQuotient(scale).norm();
  Vector5d q = Vector5d::Zero();
  Progress progress("free flexion angles", angles_deg.size());
  for (std::size_t a = 0; a < angles_deg.size(); ++a) {
    const double angle = angles_deg[a];
    const auto start = std::chrono::steady_clock::now();
    FreeAngle at;
    at.angle_deg = angle;
    std::string failure;
    // From the last angle's pose. (Carrying the path on linearly from the last two angles
    // started the ligaments' first move 30 degrees away from an overshot pose: the sweep took
    // 1.3 times as long.)
    if (!knee.move(angle, q, failure)) {
      result.failure = fmt::format("flexion to {} deg: {}", angle, failure);
      return result;
    }
    double energy = knee.potential(FreePose(jcs, angle, q), q, &at.articular);
    for (int iteration = 0;; ++iteration) {
      const FreePose pose(jcs, angle, q);
      Vector5d gradient = load_gradient(settings.loads);
      Matrix5d hessian = Matrix5d::Zero();
      double force_scale = load_scale;
      at.ligament_femur_forces_n.clear();
      for (const LigamentAtPose& l : ligaments) {
        gradient += l.generalized_force(pose);
        at.ligament_femur_forces_n.push_back(l.femur_force());
        force_scale = std::max(force_scale, l.femur_force().norm());
      }
      if (articular) {
        gradient += at.articular.gradient;
        force_scale = std::max(force_scale,
                               (at.articular.medial_force_n + at.articular.lateral_force_n).norm());
      }
      const Vector5d scaled = gradient.cwiseQuotient(scale);
      at.residual_force_n = scaled.tail<3>().norm();
      at.residual_moment_nmm = gradient.head<2>().norm();
      at.force_scale_n = force_scale;
      at.iterations = iteration;
      // What the settings promise: the force, and the moment over the rotation scale, each
      // under the tolerance's share of the largest force (a nanonewton for a knee with none).
      const double allowed = settings.tolerance * force_scale + 1e-9;
      if (at.residual_force_n <= allowed && scaled.head<2>().norm() <= allowed) {
        at.converged = true;
        break;
      }
      if (iteration == settings.max_iterations) {
        result.failure = fmt::format(
            "flexion to {} deg: the femur found no equilibrium in {} iterations (residual force "
            "{:.3g} N, moment {:.3g} N mm, against {:.3g} N)",
            angle, iteration, at.residual_force_n, at.residual_moment_nmm, force_scale);
        result.angles.push_back(at);
        return result;
      }
      hessian += knee.stiffness(pose);
      if (articular)
        hessian += at.articular.hessian;
      const Matrix5d scaled_hessian =
          hessian.cwiseQuotient(scale * scale.transpose()); // d^2 / (dq_k s_k dq_l s_l)
      const Vector5d direction =
          newton_direction(scaled_hessian, scaled, settings.max_step_mm).cwiseQuotient(scale);
      // Backtracking on the knee's potential energy, each trial from the equilibrium at q (the
      // ligaments' solves then start from the equilibrium their stiffness predicts, where from
      // the rejected longer step an MCL took up to 106 Newton iterations).
      const std::vector<LigamentAtPose::Equilibrium> at_q = knee.equilibria();
      double step = 1.0;
      bool accepted = false;
      for (int trial = 0; trial < max_line_search && !accepted; ++trial, step *= 0.5) {
        if (trial > 0)
          knee.restore(at_q);
        const Vector5d candidate = q + step * direction;
        if (const int k = runaway(candidate, settings); k >= 0) {
          if (trial + 1 < max_line_search)
            continue;
          result.failure = fmt::format(
              "flexion to {} deg: the femur's {} ran away (the ligaments and the articular "
              "contact do not hold the loads: compression {} N, anterior {} N, valgus {} N m, "
              "internal {} N m)",
              angle, coordinate_value(k, candidate), settings.loads.compression_n,
              settings.loads.anterior_n, settings.loads.valgus_nm, settings.loads.internal_nm);
          return result;
        }
        if (!knee.move(angle, candidate, failure))
          continue;
        ArticularState state;
        const double trial_energy =
            knee.potential(FreePose(jcs, angle, candidate), candidate, &state);
        // Energies of hundreds of N mm: a decrease below their round-off counts as none.
        const double round_off = 1e-11 * std::abs(energy);
        if (trial_energy <= energy + armijo * step * gradient.dot(direction) + round_off) {
          q = candidate;
          energy = trial_energy;
          at.articular = state;
          accepted = true;
        }
      }
      if (!accepted) {
        result.failure =
            fmt::format("flexion to {} deg: no trial pose could be solved ({})", angle, failure);
        return result;
      }
    }
    at.pose = joint_pose_of(angle, q);
    for (const LigamentAtPose& l : ligaments)
      at.ligament_positions.push_back(l.positions());
    at.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    result.angles.push_back(at);
    progress.advance();
  }
  progress.finish();
  result.success = true;
  return result;
}

} // namespace ligsim::sim
