#include "pipeline/stage_graph/ligament_defaults.hpp"

#include <algorithm>
#include <cctype>

namespace ligsim::pipeline {

namespace {

/// Weiss' law in FEBio's transversely isotropic Mooney-Rivlin form (C1 = mu / 2; the fiber
/// expressions give lambda dF/dlambda; K/2 (ln J)^2), as the Open Knee(s) models and Pena et al.
/// (J Biomech 2006;39:1686) give it.
MaterialDefaults febio_form(double c1_mpa, double c3_mpa, double c4, double c5_mpa,
                            double lambda_star, double bulk_mpa)
{
  MaterialDefaults m;
  m.mu_mpa = 2.0 * c1_mpa;
  m.c3_mpa = c3_mpa;
  m.c4 = c4;
  m.c5_mpa = c5_mpa;
  m.lambda_star = lambda_star;
  m.bulk_modulus_mpa = bulk_mpa;
  m.fiber_convention = "weiss";
  m.volumetric = "lnj";
  return m;
}

} // namespace

std::optional<LigamentDefaults> ligament_defaults(const std::string& name)
{
  std::string key = name;
  std::transform(key.begin(), key.end(), key.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  // Failure strain: only the MCL's is measured on human tissue here (Quapp & Weiss, J Biomech
  // Eng 1998;120:757); the others take it until a cited figure replaces it.
  const char* mcl_strain = "failure strain of the human MCL (Quapp & Weiss 1998)";
  // Gardiner & Weiss' human MCL (J Orthop Res 2003;21:1098). Its ground substance, mu = 2 C1 =
  // 2.88 MPa, gives a transverse tensile modulus 3 mu = 8.6 MPa, inside the 11.0 +- 3.6 MPa that
  // Quapp & Weiss measured across human MCL fibers; the ligament paper's mu = 27.7 MPa gives 83.
  const MaterialDefaults human_mcl = febio_form(1.44, 0.57, 48.0, 467.1, 1.063, 793.65);
  LigamentDefaults d;
  if (key == "MCL") {
    d.material = human_mcl;
    d.material_source = "Gardiner & Weiss 2003 (human MCL)";
    d.failure_load_n = 799.0;
    d.failure_source = std::string(mcl_strain) + "; 799 N (Wilson et al. 2012)";
    return d;
  }
  if (key == "LCL") {
    d.material = human_mcl;
    d.material_source = "Gardiner & Weiss 2003 MCL values, used for the LCL by Pena et al. 2006";
    d.failure_load_n = 392.0;
    d.failure_source = std::string(mcl_strain) + " (assumed); 392 N (Wilson et al. 2012)";
    return d;
  }
  if (key == "ACL") {
    d.material = febio_form(1.95, 0.0139, 116.22, 535.039, 1.046, 146.41);
    d.material_source = "Pena et al. 2006 (ACL)";
    d.failure_load_n = 658.0;
    d.failure_source =
        std::string(mcl_strain) + " (assumed); 658 N, donors 60-97 y (Woo et al. 1991)";
    return d;
  }
  if (key == "PCL") {
    d.material = febio_form(3.25, 0.1196, 87.178, 431.063, 1.035, 243.9);
    d.material_source = "Pena et al. 2006 (PCL)";
    d.failure_load_n = 1620.0;
    d.failure_source = std::string(mcl_strain) +
                       " (assumed); 1,620 N, anterolateral bundle (Race & Amis 1994, unverified)";
    return d;
  }
  return std::nullopt;
}

} // namespace ligsim::pipeline
