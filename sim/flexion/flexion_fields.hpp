#pragma once
/// @brief Every key of a flexion config with the setting it sets, listed once per table. The
/// reader (flexion_config.cpp) and the writer of the settings (summary.json's
/// `parameters.config`) both walk these lists, so neither can miss a key. Each visit_*(s, visit)
/// calls visit(key, member), or visit(key, choice(...)) for an enumerated one; `s` may be const
/// (writing) or not (reading). A few keys are read by hand beside them, and say so.

#include "common/config_choice.hpp"
#include "sim/flexion/flexion_settings.hpp"
#include "sim/material/material_fields.hpp"
#include "sim/scene/contact_table.hpp"
#include "sim/solver/newton_fields.hpp"

namespace ligsim::sim {

/// [contact] initial_overlap's text for ContactConfig::reshape_overlap.
inline std::string initial_overlap_name(bool reshape)
{
  return reshape ? "reshape" : "deform";
}

/// The top level, besides `model` (a path from the config's folder, read by hand).
template <class S, class Visit> void visit_flexion_top(S& s, Visit&& visit)
{
  visit("angles_deg", s.angles_deg);
  visit("mode", choice(s.mode, to_string, {FlexionMode::quasi_static, FlexionMode::interactive}));
  visit("images", s.images);
  visit("image_angles_deg", s.image_angles_deg);
  visit("ligaments", s.ligaments);
  visit("without", s.without);
}

template <class S, class Visit> void visit_axis(S& a, Visit&& visit)
{
  using Source = AxisSettings::Source;
  visit("method",
        choice(a.source, to_string, {Source::condyles, Source::transepicondylar, Source::points}));
  visit("first_mm", a.first_mm);
  visit("second_mm", a.second_mm);
  visit("posterior", a.posterior);
  visit("medial_epicondyle_mm", a.medial_epicondyle_mm);
  visit("lateral_epicondyle_mm", a.lateral_epicondyle_mm);
}

template <class S, class Visit> void visit_anatomy(S& a, Visit&& visit)
{
  visit("side", a.side);
  visit("proximal", a.proximal);
  visit("posterior", a.posterior);
}

/// Besides `table` (a path from the config's folder, read by hand).
template <class S, class Visit> void visit_motion(S& m, Visit&& visit)
{
  using Path = MotionSettings::Path;
  visit("path", choice(m.path, to_string,
                       {Path::automatic, Path::free, Path::pure, Path::passive, Path::table}));
  visit("coupled_translations", m.coupled_translations);
}

template <class S, class Visit> void visit_ligament(S& l, Visit&& visit)
{
  visit("name", l.name);
  visit("failure_strain", l.failure_strain);
  visit("failure_load_n", l.failure_load_n);
  visit("strain_region_radius_mm", l.strain_region_radius_mm);
}

/// [material]: the material of every ligament, and the in-situ strain.
template <class S, class Visit> void visit_material(S& s, Visit&& visit)
{
  visit_weiss_material(s.material, visit);
  visit("in_situ_strain", s.in_situ_strain);
}

template <class S, class Visit> void visit_interactive(S& i, Visit&& visit)
{
  visit("angular_speed_deg_s", i.angular_speed_deg_s);
  visit("time_step_s", i.time_step_s);
  visit("density_kg_m3", i.density_kg_m3);
  visit("mass_damping_per_s", i.mass_damping_per_s);
  visit("linear_solver",
        choice(i.linear_solver, to_string, {LinearSolverKind::direct, LinearSolverKind::pcg}));
  visit("max_iterations", i.max_iterations);
  visit("iteration_tolerance", i.iteration_tolerance);
}

/// [contact]: the keys scenes share (visit_contact), then the flexion's own.
template <class S, class Visit> void visit_flexion_contact(S& c, Visit&& visit)
{
  visit_contact(c, visit);
  visit("bones", c.bones);
  visit("initial_overlap", choice(c.reshape_overlap, initial_overlap_name, {false, true}));
}

template <class S, class Visit> void visit_loads(S& l, Visit&& visit)
{
  visit("compression_n", l.compression_n);
  visit("anterior_n", l.anterior_n);
  visit("valgus_nm", l.valgus_nm);
  visit("internal_nm", l.internal_nm);
}

/// [articular]: the free knee's femur-tibia contact.
template <class S, class Visit> void visit_articular(S& f, Visit&& visit)
{
  visit("enabled", f.articular_contact);
  visit("modulus_mpa", f.articular.modulus_mpa);
  visit("poisson", f.articular.poisson);
  visit("thickness_mm", f.articular.thickness_mm);
  visit("gap_mm", f.articular.gap_mm);
  visit("seated", f.articular.seated);
}

template <class S, class Visit> void visit_free(S& f, Visit&& visit)
{
  visit("tolerance", f.tolerance);
  visit("max_iterations", f.max_iterations);
  visit("rotation_scale_mm", f.rotation_scale_mm);
  visit("max_step_mm", f.max_step_mm);
  visit("max_translation_mm", f.max_translation_mm);
  visit("max_rotation_deg", f.max_rotation_deg);
}

/// Every table of the config with its settings: visit_table(name, settings, visit_fields); the
/// top level first, under the name "".
template <class S, class VisitTable> void visit_flexion_tables(S& s, VisitTable&& visit_table)
{
  visit_table("", s, [](auto& p, auto&& v) { visit_flexion_top(p, v); });
  visit_table("axis", s.axis, [](auto& p, auto&& v) { visit_axis(p, v); });
  visit_table("anatomy", s.anatomy, [](auto& p, auto&& v) { visit_anatomy(p, v); });
  visit_table("motion", s.motion, [](auto& p, auto&& v) { visit_motion(p, v); });
  visit_table("ligament", s.ligament, [](auto& p, auto&& v) { visit_ligament(p, v); });
  visit_table("material", s, [](auto& p, auto&& v) { visit_material(p, v); });
  visit_table("static", s.newton, [](auto& p, auto&& v) { visit_newton_iteration(p, v); });
  visit_table("interactive", s.interactive, [](auto& p, auto&& v) { visit_interactive(p, v); });
  visit_table("contact", s.contact, [](auto& p, auto&& v) { visit_flexion_contact(p, v); });
  visit_table("loads", s.free.loads, [](auto& p, auto&& v) { visit_loads(p, v); });
  visit_table("articular", s.free, [](auto& p, auto&& v) { visit_articular(p, v); });
  visit_table("free", s.free, [](auto& p, auto&& v) { visit_free(p, v); });
}

} // namespace ligsim::sim
