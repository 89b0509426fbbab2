#include "pipeline/stage_graph/ligament_defaults.hpp"

#include "stages/anatomy/part_names.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace ligsim::pipeline {

namespace {

/// Weiss' law in FEBio's transversely isotropic Mooney-Rivlin form (C1 = mu / 2; the fiber
/// expressions give lambda dF/dlambda; K/2 (ln J)^2), as the Open Knee(s) models and Pena et al.
/// (J Biomech 2006;39:1686) give it.
sim::MaterialParameters febio_form(double c1_mpa, double c3_mpa, double c4, double c5_mpa,
                                   double lambda_star, double bulk_mpa)
{
  sim::MaterialParameters m;
  m.mu_mpa = 2.0 * c1_mpa;
  m.bulk_modulus_mpa = bulk_mpa;
  m.volumetric = sim::VolumetricLaw::lnj;
  m.fiber = sim::FiberParameters{c3_mpa, c4, c5_mpa, lambda_star, sim::FiberConvention::weiss};
  return m;
}

/// A collateral's femoral footprint: a disc of 6 mm radius `proximal_mm` and `posterior_mm` from
/// its epicondyle, held to the ligament (snapped to it where the point misses it), no farther
/// from the epicondyle than its published offset plus the disc's radius, and no larger than
/// twice its published area.
attachments::Rule collateral_femoral(const char* epicondyle, double proximal_mm,
                                     double posterior_mm, double published_mm2)
{
  attachments::Rule r;
  r.rule = "landmark";
  r.landmark = epicondyle;
  r.proximal_mm = proximal_mm;
  r.posterior_mm = posterior_mm;
  r.radius_mm = 6.0;
  r.snap = true;
  r.max_distance_mm = std::hypot(proximal_mm, posterior_mm) + r.radius_mm;
  r.max_area_mm2 = 2.0 * published_mm2;
  return r;
}

attachments::Rule end_rule(const char* end, double length_mm)
{
  attachments::Rule r;
  r.rule = "end";
  r.end = end;
  r.end_length_mm = length_mm;
  return r;
}

attachments::Rule proximity(double distance_mm)
{
  attachments::Rule r;
  r.rule = "proximity";
  r.distance_mm = distance_mm;
  return r;
}

} // namespace

std::optional<LigamentDefaults> ligament_defaults(const std::string& name)
{
  std::string key = name;
  if (const auto part = anatomy::recognise_part(name); part && anatomy::is_ligament(*part))
    key = anatomy::part_name(*part);
  std::transform(key.begin(), key.end(), key.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  // Failure strain: only the MCL's is measured on human tissue here (Quapp & Weiss, J Biomech
  // Eng 1998;120:757); the others take it until a cited figure replaces it.
  const char* mcl_strain = "failure strain of the human MCL (Quapp & Weiss 1998)";
  // Gardiner & Weiss' human MCL (J Orthop Res 2003;21:1098). Its ground substance, mu = 2 C1 =
  // 2.88 MPa, gives a transverse tensile modulus 3 mu = 8.6 MPa, inside the 11.0 +- 3.6 MPa that
  // Quapp & Weiss measured across human MCL fibers; the ligament paper's mu = 27.7 MPa gives 83.
  const sim::MaterialParameters human_mcl = febio_form(1.44, 0.57, 48.0, 467.1, 1.063, 793.65);
  LigamentDefaults d;
  if (key == "MCL") {
    d.material = human_mcl;
    d.material_source = "Gardiner & Weiss 2003 (human MCL)";
    d.failure_load_n = 799.0;
    d.failure_source = std::string(mcl_strain) + "; 799 N (Wilson et al. 2012)";
    d.femur_footprint = collateral_femoral("medial_epicondyle", 3.2, 4.8, 79.7);
    d.distal_footprint = end_rule("distal", 15.0);
    d.distal_footprint.bone_distance_mm = 2.0;
    d.footprint_source = "femoral: 3.2 mm proximal, 4.8 mm posterior of the medial epicondyle "
                         "(LaPrade et al. 2007), 79.7 mm^2 (Liu et al. 2010); tibial: its distal "
                         "15 mm where it lies within 2 mm of the tibia (data/hra-knee/knee.toml)";
    return d;
  }
  if (key == "LCL") {
    d.material = human_mcl;
    d.material_source = "Gardiner & Weiss 2003 MCL values, used for the LCL by Pena et al. 2006";
    d.failure_load_n = 392.0;
    d.failure_source = std::string(mcl_strain) + " (assumed); 392 N (Wilson et al. 2012)";
    d.femur_footprint = collateral_femoral("lateral_epicondyle", 1.4, 3.1, 48.0);
    d.distal_footprint = proximity(2.6);
    d.distal_bone = "fibula";
    d.footprint_source = "femoral: 1.4 mm proximal, 3.1 mm posterior of the lateral epicondyle, "
                         "43-52 mm^2 (LaPrade et al. 2003); fibular: within 2.6 mm of the "
                         "fibula (data/hra-knee/knee.toml)";
    return d;
  }
  if (key == "ACL") {
    d.material = febio_form(1.95, 0.0139, 116.22, 535.039, 1.046, 146.41);
    d.material_source = "Pena et al. 2006 (ACL)";
    d.failure_load_n = 658.0;
    d.failure_source =
        std::string(mcl_strain) + " (assumed); 658 N, donors 60-97 y (Woo et al. 1991)";
    d.femur_footprint = end_rule("proximal", 6.0);
    d.distal_footprint = proximity(3.2);
    d.footprint_source = "femoral: its proximal 6 mm, on the lateral condyle's notch wall; "
                         "tibial: within 3.2 mm of the tibia (data/hra-knee/knee.toml; 135.2 "
                         "+- 15.1 mm^2 in Araki et al. 2017)";
    return d;
  }
  if (key == "PCL") {
    d.material = febio_form(3.25, 0.1196, 87.178, 431.063, 1.035, 243.9);
    d.material_source = "Pena et al. 2006 (PCL)";
    d.failure_load_n = 1620.0;
    d.failure_source = std::string(mcl_strain) +
                       " (assumed); 1,620 N, anterolateral bundle (Race & Amis 1994, unverified)";
    d.femur_footprint = end_rule("proximal", 6.0);
    d.distal_footprint = proximity(4.0);
    d.footprint_source = "femoral: its proximal 6 mm, on the medial condyle's notch wall; "
                         "tibial: within 4.0 mm of the tibia (data/hra-knee/knee.toml)";
    return d;
  }
  return std::nullopt;
}

} // namespace ligsim::pipeline
