#include "sim/febio/febio_cross_check.hpp"

#include "common/error.hpp"
#include "common/resources.hpp"
#include "sim/febio/feb_writer.hpp"

#include <chrono>

namespace ligsim::sim {

CrossCheck cross_check_with_febio(const KneeModel& given, const FlexionSettings& settings,
                                  const KneeMotion& motion, const std::filesystem::path& febio,
                                  const std::filesystem::path& out, double extra_wall_s,
                                  const FebContactSettings& febio_contact)
{
  if (settings.mode != FlexionMode::quasi_static)
    fail("verify febio: the comparison is quasi-static (FEBio solves equilibria): set mode = "
         "\"static\"");
  CrossCheck check;
  const auto start = std::chrono::steady_clock::now();
  const BoundaryConditions conditions = knee_conditions(given, femur_rigid_motion(motion));
  const SweepSteps steps = motion_steps(motion);
  // Reshaped, both programs start from the shape pushed out of the bones.
  KneeModel model = feb_start_model(given, settings, conditions);
  if (model.fiber_directions_at_points.rows() > 0) {
    // FEBio's file takes one fiber per element: both programs use the element's.
    model.fiber_directions_at_points.resize(0, 3);
    check.warnings.push_back("the model's fibers at the quadrature points are replaced by each "
                             "tet's own fiber in both programs: FEBio's file takes one per tet");
  }
  const HyperelasticBody body = ligament_body(model, settings.material, settings.in_situ_strain);
  const KneeContact contact(model, conditions, settings.contact, settings.model_dir / "contact");
  const SweepResult sweep = run_flexion_sweep(body, conditions, settings, {}, &contact, &steps);
  check.ours_wall_s = seconds_since(start) + extra_wall_s;
  if (!sweep.success)
    fail<SolverError>("verify febio: ligsim's sweep stopped: {}", sweep.failure);
  check.ours = sweep.angles;

  const FebProblem problem = knee_feb_problem(
      model, settings, conditions, steps, motion.axis.axis.point_mm, check.warnings, febio_contact);
  check.feb = out / "knee.feb";
  write_feb(check.feb, problem);
  check.run = run_febio(febio, check.feb);
  check.febio = febio_steps(check.run.parsed, problem, feb_femur, body);
  for (std::size_t k = 0; k < check.febio.size(); ++k) {
    Eigen::VectorXd gap_mm;
    Eigen::VectorXd pressure_mpa;
    check.febio_contact.push_back(
        contact.measure(check.febio[k].x, steps.load_factors[k], false, gap_mm, pressure_mpa));
  }

  for (std::size_t k = 0; k < check.ours.size(); ++k) {
    const AngleResult& ours = check.ours[k];
    Eigen::Vector3d femur = ours.femur_force_n;
    for (const BoneContact& bone : ours.contact)
      if (bone.bone == "femur" && bone.in_solve)
        femur += bone.force_n;
    ComparisonRow row;
    row.angle_deg = ours.angle_deg;
    row.ours_femur_force_n = femur.norm();
    row.febio_femur_force_n = check.febio[k].femur_force_n.norm();
    row.ours_energy_mj = ours.strain_energy_mj;
    row.febio_energy_mj = check.febio[k].strain_energy_mj;
    row.ours_mean_fiber_stretch = ours.mean_fiber_stretch;
    row.febio_mean_fiber_stretch = check.febio[k].mean_fiber_stretch;
    row.ours_wall_s = check.ours_wall_s;
    row.febio_wall_s = check.run.wall_s;
    check.rows.push_back(row);
  }
  return check;
}

} // namespace ligsim::sim
