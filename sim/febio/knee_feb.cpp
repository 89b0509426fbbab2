#include "sim/febio/knee_feb.hpp"

#include "common/error.hpp"
#include "sim/contact/bone_penetration.hpp"
#include "sim/contact/contact_surface.hpp"
#include "sim/flexion/femur_poses.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace ligsim::sim {

namespace {

std::string joined(const std::vector<double>& values)
{
  std::string text;
  for (double v : values)
    text += (text.empty() ? "" : ", ") + fmt::format("{}", v);
  return text;
}

std::string joined_text(const std::vector<std::string>& items)
{
  std::string text;
  for (std::size_t i = 0; i < items.size(); ++i)
    text += (i == 0 ? "" : (i + 1 == items.size() ? " and " : ", ")) + items[i];
  return text;
}

std::string number_text(double value)
{
  return fmt::format("{}", value);
}

/// How deep the ligament's surface nodes that are not bound to `bone` lie inside its triangles
/// at rest (0 when none is inside), mm.
double deepest_overlap_mm(const TetMesh& ligament, const FebRigidBody& bone)
{
  std::vector<bool> bound(static_cast<std::size_t>(ligament.V.rows()), false);
  for (int node : bone.attached_nodes)
    bound[static_cast<std::size_t>(node)] = true;
  const BonePenetration penetration(bone.surface);
  double deepest = 0.0;
  for (int node : boundary_surface(ligament).nodes)
    if (!bound[static_cast<std::size_t>(node)])
      deepest = std::max(deepest, penetration.depth_mm(ligament.V.row(node).transpose()));
  return deepest;
}

} // namespace

KneeModel feb_start_model(const KneeModel& model, const FlexionSettings& settings,
                          const BoundaryConditions& conditions, OverlapReport* report)
{
  if (!settings.contact.reshape_overlap || !settings.contact.enabled.value_or(true))
    return model;
  const KneeContact contact(model, conditions, settings.contact, settings.model_dir / "contact");
  return with_overlap_reshaped(model, settings, conditions, contact, report);
}

FebProblem knee_feb_problem(const KneeModel& model, const FlexionSettings& settings,
                            const BoundaryConditions& conditions, const SweepSteps& steps,
                            const Eigen::Vector3d& center_mm, std::vector<std::string>& warnings,
                            const FebContactSettings& contact)
{
  FebProblem problem;
  problem.contact_settings = contact;
  problem.ligament = model.mesh;
  problem.ligament_tet10 = model.tet10;
  problem.fiber_directions = model.fiber_directions;
  if (model.fiber_directions_at_points.rows() > 0)
    warnings.push_back("FEBio gets one fiber per tet, the tet's own: the model's fibers at the "
                       "quadrature points of its 10-node tets do not go into the file");
  problem.material = settings.material;
  problem.in_situ_strain = settings.in_situ_strain;
  problem.step_labels = steps.angles_deg;
  problem.contact = settings.contact.enabled.value_or(true);

  FebRigidBody femur;
  femur.name = "femur";
  femur.surface = *model.femur;
  femur.center_mm = center_mm;
  femur.attached_nodes = nodes_bound_to(model, "femur");
  femur.poses = femur_poses(conditions, steps);
  // A found path starts off the built pose: FEBio settles the prestrain there first.
  const Eigen::Isometry3d& first = femur.poses.front();
  if ((first.matrix() - Eigen::Matrix4d::Identity()).cwiseAbs().maxCoeff() > 1e-12)
    problem.settle_steps = 1;
  const std::vector<std::string> in_contact = contact_bones(model, settings.contact.bones);
  const auto takes_contact = [&](const std::string& bone) {
    return problem.contact &&
           std::find(in_contact.begin(), in_contact.end(), bone) != in_contact.end();
  };
  femur.contact = takes_contact("femur");
  if (!bone_of(model, model.distal_bone))
    throw InputError("the model's distal footprint is bound to the " + model.distal_bone +
                     ", which the model has no surface of");
  problem.bones = {femur};
  // The fixed bones, the fibula where the knee has one: the distal footprint is bound to its own
  // bone (an LCL's to the fibula), and the ligament slides on the others, as in `ligsim flexion`.
  for (const char* name : {"tibia", "fibula"}) {
    const TriangleSurface* surface = bone_of(model, name);
    if (!surface)
      continue;
    FebRigidBody bone;
    bone.name = name;
    bone.surface = *surface;
    bone.center_mm = surface->V.colwise().mean().transpose();
    bone.attached_nodes = nodes_bound_to(model, name);
    bone.contact = takes_contact(name);
    problem.bones.push_back(std::move(bone));
  }
  // The same start as ligsim's pre-push (sim/flexion/initial_overlap): each bone the ligament
  // overlaps as segmented starts shrunk by the deepest overlap plus half of d_hat.
  std::vector<std::string> overlaps;
  double deepest_of_all = 0.0;
  for (FebRigidBody& bone : problem.bones) {
    const double deepest = bone.contact ? deepest_overlap_mm(model.mesh, bone) : 0.0;
    deepest_of_all = std::max(deepest_of_all, deepest);
    if (deepest > 0.0) {
      bone.contact_start_offset_mm = deepest + 0.5 * settings.contact.barrier.d_hat_mm;
      overlaps.push_back(fmt::format("the {} by up to {:.3g} mm (its contact offset starts at "
                                     "-{:.3g} mm)",
                                     bone.name, deepest, bone.contact_start_offset_mm));
    }
  }

  if (!overlaps.empty() && settings.contact.reshape_overlap)
    warnings.push_back(fmt::format(
        "[contact] initial_overlap = \"reshape\": the ligament's shape here still lies up to "
        "{:.3g} mm inside a bone by its triangles (after ligsim's push, which keeps nodes "
        "outside the bone's distance grid, a few thousandths of a millimetre; more: the shape "
        "was not pushed, see with_overlap_reshaped), and FEBio pushes that out as a deformation "
        "during step 1",
        deepest_of_all));

  const MaterialParameters& m = settings.material;
  std::vector<std::string>& notes = problem.notes;
  notes.push_back("Written by `ligsim export febio` from the knee model in " +
                  settings.model_dir.string() + ": the problem `ligsim flexion` solves.");
  notes.push_back(
      std::string("Units: mm, N, MPa. ") +
      (problem.settle_steps > 0 ? "Time 1 is the built pose, where the in-situ prestrain "
                                  "settles; time k + 1 is the flexion angle number k of: "
                                : "Time k is the flexion angle number k of: ") +
      joined(steps.angles_deg) +
      " deg; the femur's pose is prescribed exactly at each time (its six rigid degrees of freedom "
      "follow load curves 2-7), the tibia" +
      std::string(model.fibula ? " and the fibula are" : " is") + " fixed.");
  notes.push_back(fmt::format(
      "Material: Weiss' transversely isotropic law, mu = {} MPa (c1 = mu/2), K = {} MPa with {} "
      "(pressure_model {}), fiber c3 = {} MPa, c4 = {}, c5 = {} MPa, lambda* = {}; fiber "
      "directions per tet in MeshData 'fiber'.",
      m.mu_mpa, m.bulk_modulus_mpa,
      m.volumetric == VolumetricLaw::jm1 ? "U = K/2 (J-1)^2" : "U = K/2 (ln J)^2",
      m.volumetric == VolumetricLaw::jm1 ? "Abaqus" : "default", m.fiber->c3_mpa, m.fiber->c4,
      m.fiber->c5_mpa, m.fiber->lambda_star));
  if (settings.in_situ_strain != 0.0)
    notes.push_back(fmt::format(
        "In-situ strain {}: the fiber term alone is pre-stretched by {} along the fiber "
        "(isochoric in-situ stretch of FEBio's uncoupled prestrain material, ramped from 1 over "
        "the first step by its load curve), the ground "
        "substance is not; together the mixture is trans iso Mooney-Rivlin with |a| = 1 + "
        "strain, as in ligsim. FEBio reports no strain energy for its prestrain material: its "
        "logged sed then holds the ground substance and volume terms only.",
        settings.in_situ_strain, 1.0 + settings.in_situ_strain));
  if (m.fiber->convention == FiberConvention::paper) {
    const std::string warning =
        "the model's fiber convention is 'paper' (the expressions give dW/dlambda), but FEBio "
        "implements only Weiss' convention (they give lambda dW/dlambda): this file uses "
        "FEBio's law with the same constants, a fiber softer by the factor lambda than the "
        "model's; set convention = \"weiss\" for the same problem in both";
    warnings.push_back(warning);
    notes.push_back("WARNING: " + warning + ".");
  }
  if (problem.contact) {
    notes.push_back(fmt::format(
        "Contact: frictionless sliding-elastic of the ligament's free surface on the bones, "
        "penalty method with FEBio's automatic penalty scaled by {} (the default 1 lets the "
        "ligament into the bone several times deeper; ligsim's barrier keeps a gap instead, "
        "and both tend to the same contact as the gap and the penetration vanish). Its exact "
        "stiffness is not symmetric, and FEBio's skyline solver (the direct solver of a build "
        "without MKL) takes symmetric matrices only; the contact is asked for its symmetrized "
        "stiffness (symmetric_stiffness 1), which leaves the residual, hence the answer, "
        "unchanged and only slows Newton's convergence. BiCGSTAB on the exact matrix failed on "
        "the shipped MCL (no preconditioner in this build).",
        number_text(problem.contact_settings.penalty)));
    notes.push_back(
        overlaps.empty()
            ? std::string(settings.contact.reshape_overlap
                              ? "The ligament does not overlap the bones at rest: with [contact] "
                                "initial_overlap = \"reshape\", where the segmented ligament "
                                "overlapped a bone its nodes here are the rest shape ligsim "
                                "pushed out of the bones (without the in-situ strain), so neither "
                                "program repeats the push."
                              : "The ligament does not overlap the bones at rest.")
            : "The ligament overlaps " + joined_text(overlaps) +
                  " at rest, as segmented. ligsim pushes it out before the knee moves, growing "
                  "the bones from shrunk back to their surfaces; here the same happens during "
                  "step 1: the contact offset (negative: the bone shrunk) is ramped linearly to 0 "
                  "by its own load curve, so that no node starts deep inside a bone, where the "
                  "penalty would push it out in one jump and invert elements.");
  } else {
    notes.push_back(
        "No contact: the stiffness is symmetric, so FEBio's default skyline solver works.");
  }
  if (problem.contact) {
    // The symmetrized contact stiffness makes Newton converge linearly; FEBio's relative
    // displacement criterion then costs about ten more reformations per time step than the
    // residual and energy criteria, and its automatic stepper answers by shrinking the steps
    // without end (docs/knee.md, "FEBio cross-check on the HRA knee").
    problem.solver.displacement_tolerance = 0.0;
    notes.push_back("Contact on: dtol 0 switches FEBio's displacement criterion off (with the "
                    "symmetrized stiffness Newton converges linearly, and that criterion kept "
                    "its time steps shrinking); the residual and energy criteria decide.");
  }
  const FebSolverSettings& solver = problem.solver;
  notes.push_back(fmt::format(
      "Solver: full Newton (BFGS with max_ups 0: a reformation every iteration), dtol {}, etol "
      "{}, rtol {}; optimize_bw renumbers the equations for a narrow skyline profile "
      "(without it FEBio spent over 3 minutes on the shipped MCL's first step, with it under a "
      "minute on the whole sweep). The .log holds the ligament's node positions (record 1), the "
      "rigid bodies' "
      "positions, rotations, reaction forces and moments (record 2) and the tets' strain energy "
      "density (record 3) at each step.",
      solver.displacement_tolerance, solver.energy_tolerance, solver.residual_tolerance));
  if (settings.mode == FlexionMode::interactive)
    notes.push_back("The config's interactive mode has no FEBio counterpart here: the file "
                    "solves the quasi-static sweep.");
  return problem;
}

} // namespace ligsim::sim
