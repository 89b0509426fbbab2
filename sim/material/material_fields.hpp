#pragma once
/// @brief The Weiss material's keys, listed once. A flexion config's and a build config's
/// [material] hold them all; a scene splits them between [material] (the ground substance) and
/// [fibers] (the fiber law). Each visit_*(m, visit) calls visit(key, member) or
/// visit(key, choice(...)), as the configs' other key lists do (common/config_section.hpp reads
/// them, common/fields_json.hpp writes them).

#include "common/config_choice.hpp"
#include "sim/material/material_parameters.hpp"

namespace ligsim::sim {

/// The enumerated keys, as every material list names their values.
template <class M> auto volumetric_law(M& m)
{
  return choice(m.volumetric, to_string, {VolumetricLaw::jm1, VolumetricLaw::lnj});
}

template <class F> auto fiber_convention(F& f)
{
  return choice(f.convention, to_string, {FiberConvention::paper, FiberConvention::weiss});
}

/// The ground substance and the volumetric penalty.
template <class M, class Visit> void visit_ground_substance(M& m, Visit&& visit)
{
  visit("mu_mpa", m.mu_mpa);
  visit("k_mpa", m.bulk_modulus_mpa);
  visit("volumetric", volumetric_law(m));
}

/// The fiber law.
template <class F, class Visit> void visit_fiber_law(F& f, Visit&& visit)
{
  visit("c3_mpa", f.c3_mpa);
  visit("c4", f.c4);
  visit("c5_mpa", f.c5_mpa);
  visit("lambda_star", f.lambda_star);
  visit("convention", fiber_convention(f));
}

/// Both, as one table; the material has fibers.
template <class M, class Visit> void visit_weiss_material(M& m, Visit&& visit)
{
  visit_ground_substance(m, visit);
  visit_fiber_law(*m.fiber, visit);
}

} // namespace ligsim::sim
