#include "sim/febio/febio_comparison.hpp"

#include "common/error.hpp"
#include "sim/flexion/knee_flexion.hpp"

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <cmath>
#include <iterator>

namespace ligsim::sim {

namespace {

/// The record of labelled step `step`, which ends at time settle + step + 1.
const FebioRecord& record_at(const FebioLog& log, FebLogRecord which, std::size_t step, int settle,
                             double angle_deg)
{
  const std::size_t time = static_cast<std::size_t>(settle) + step + 1;
  const FebioRecord* record = log.find(static_cast<int>(which), static_cast<double>(time));
  if (!record)
    fail<SolverError>("FEBio's log has no data record #{} at time {} (the step of {} deg)",
                      static_cast<int>(which), time, angle_deg);
  return *record;
}

const std::vector<double>& row_of(const FebioRecord& record, int id, const std::string& what)
{
  const auto found = record.rows.find(id);
  if (found == record.rows.end())
    fail<SolverError>("FEBio's log, data record #{} at time {}: no row for {} {}", record.record,
                      record.time, what, id);
  return found->second;
}

} // namespace

std::vector<FebioStep> febio_steps(const FebioLog& log, const FebProblem& problem,
                                   std::size_t femur, const HyperelasticBody& body)
{
  const FebRigidBody& bone = problem.bones.at(femur);
  std::vector<FebioStep> steps;
  for (std::size_t k = 0; k < problem.step_labels.size(); ++k) {
    FebioStep step;
    step.angle_deg = problem.step_labels[k];
    const FebioRecord& nodes =
        record_at(log, FebLogRecord::ligament_nodes, k, problem.settle_steps, step.angle_deg);
    step.x.resize(body.dof_count());
    for (int n = 0; n < body.node_count(); ++n) {
      const std::vector<double>& xyz = row_of(nodes, n + 1, "node");
      for (int c = 0; c < 3; ++c)
        step.x(3 * n + c) = xyz[static_cast<std::size_t>(c)];
    }
    step.strain_energy_mj = body.energy(step.x).energy;
    step.mean_fiber_stretch = measure_fibers(body, step.x).mean_fiber_stretch;

    const FebioRecord& energy =
        record_at(log, FebLogRecord::strain_energy, k, problem.settle_steps, step.angle_deg);
    for (int e = 0; e < body.element_count(); ++e)
      step.logged_energy_mj += row_of(energy, e + 1, "element")[0] * body.element_volume(e);

    // Record 2: x;y;z;qx;qy;qz;qw;Fx;Fy;Fz;...
    const FebioRecord& rigid =
        record_at(log, FebLogRecord::rigid_bodies, k, problem.settle_steps, step.angle_deg);
    const std::vector<double>& r = row_of(rigid, feb_material_id_of_bone(femur), "rigid body");
    if (r.size() < 10)
      fail<SolverError>("FEBio's log, data record #{}: {} values per rigid body, expected 13",
                        rigid.record, r.size());
    step.femur_force_n = Eigen::Vector3d(r[7], r[8], r[9]);
    const Eigen::Vector3d position(r[0], r[1], r[2]);
    const Eigen::Quaterniond rotation(r[6], r[3], r[4], r[5]);
    const Eigen::Isometry3d& pose =
        bone.poses.empty() ? Eigen::Isometry3d::Identity() : bone.poses[k];
    for (int node : bone.attached_nodes) {
      const Eigen::Vector3d rest = problem.ligament.V.row(node).transpose();
      const Eigen::Vector3d febio = position + rotation.normalized() * (rest - bone.center_mm);
      step.femur_pose_error_mm = std::max(step.femur_pose_error_mm, (febio - pose * rest).norm());
    }
    steps.push_back(step);
  }
  return steps;
}

double relative_difference(double a, double b)
{
  if (a == b)
    return 0.0;
  return (a - b) / std::abs(b);
}

std::string comparison_csv(const std::vector<ComparisonRow>& rows)
{
  fmt::memory_buffer out;
  const auto it = std::back_inserter(out);
  fmt::format_to(it, "angle_deg,ours_femur_force_n,febio_femur_force_n,ours_energy_mj,"
                     "febio_energy_mj,ours_mean_fiber_stretch,febio_mean_fiber_stretch,"
                     "ours_wall_s,febio_wall_s\n");
  for (const ComparisonRow& r : rows)
    fmt::format_to(it, "{},{},{},{},{},{},{},{:.3f},{:.3f}\n", r.angle_deg, r.ours_femur_force_n,
                   r.febio_femur_force_n, r.ours_energy_mj, r.febio_energy_mj,
                   r.ours_mean_fiber_stretch, r.febio_mean_fiber_stretch, r.ours_wall_s,
                   r.febio_wall_s);
  return fmt::to_string(out);
}

std::string comparison_table(const std::vector<ComparisonRow>& rows)
{
  fmt::memory_buffer out;
  const auto it = std::back_inserter(out);
  fmt::format_to(it, "| angle (deg) | femur force ours / FEBio (N) | diff. | strain energy ours / "
                     "FEBio (mJ) | diff. | mean fiber stretch ours / FEBio | diff. |\n"
                     "| ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
  for (const ComparisonRow& r : rows)
    fmt::format_to(it,
                   "| {} | {:.2f} / {:.2f} | {:+.1e} % | {:.2f} / {:.2f} | {:+.1e} % | {:.5f} "
                   "/ {:.5f} | {:+.1e} |\n",
                   r.angle_deg, r.ours_femur_force_n, r.febio_femur_force_n,
                   100.0 * relative_difference(r.ours_femur_force_n, r.febio_femur_force_n),
                   r.ours_energy_mj, r.febio_energy_mj,
                   100.0 * relative_difference(r.ours_energy_mj, r.febio_energy_mj),
                   r.ours_mean_fiber_stretch, r.febio_mean_fiber_stretch,
                   r.ours_mean_fiber_stretch - r.febio_mean_fiber_stretch);
  if (!rows.empty())
    fmt::format_to(it, "\nWhole run: ours {:.2f} s, FEBio {:.2f} s (ratio {:.1f}).\n",
                   rows.front().ours_wall_s, rows.front().febio_wall_s,
                   rows.front().febio_wall_s / std::max(rows.front().ours_wall_s, 1e-9));
  return fmt::to_string(out);
}

} // namespace ligsim::sim
