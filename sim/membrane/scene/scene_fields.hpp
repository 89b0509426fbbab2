#pragma once
/// @brief A tear scene's settings, listed once per table: the reader (scene_file.cpp) and the
/// writer of summary.json's `parameters.config` both walk them. Each visit_*(s, visit) calls
/// visit(key, member), visit(key, required(member)) or visit(key, degrees(radians)); `s` may be
/// const (writing) or not (reading). The mesh, the fibers, the regions and the cuts are read by
/// hand in scene_file.cpp: their keys depend on their kind.

#include "common/config_field_kinds.hpp"
#include "sim/membrane/scene/scene.hpp"

namespace ligsim::membrane {

template <class M, class Visit> void visit_membrane_material(M& m, Visit&& visit)
{
  visit("fiber_modulus_mpa", required(m.fiber_modulus_mpa));
  visit("transverse_modulus_mpa", required(m.transverse_modulus_mpa));
  visit("fiber_poisson", required(m.fiber_poisson));
  visit("shear_modulus_mpa", required(m.shear_modulus_mpa));
  visit("thickness_mm", required(m.thickness_mm));
  visit("density_t_per_mm3", required(m.density_t_per_mm3));
}

template <class T, class Visit> void visit_tearing(T& t, Visit&& visit)
{
  visit("fiber_threshold_mpa", required(t.thresholds.fiber_mpa));
  visit("transverse_threshold_mpa", required(t.thresholds.transverse_mpa));
  visit("steepness_alpha", t.thresholds.steepness);
  visit("max_turn_deg", degrees(t.thresholds.max_turn_rad));
  visit("split_faces", t.propagation.split_faces);
  visit("min_angle_deg", degrees(t.propagation.min_angle_rad));
  visit("min_area_mm2", t.propagation.min_area_mm2);
  visit("initiation", t.initiation);
  visit("initiation_clearance_mm", t.initiation_clearance_mm);
  visit("max_events_per_step", t.max_events_per_step);
}

template <class S, class Visit> void visit_membrane_solver(S& s, Visit&& visit)
{
  visit("time_step_s", required(s.time_step_s));
  visit("mass_damping_per_s", s.mass_damping_per_s);
  visit("stiffness_damping_s", s.stiffness_damping_s);
  visit("cg_tolerance", s.cg_tolerance);
  visit("cg_max_iterations", s.cg_max_iterations);
}

/// Besides `centre_mm` (a point, read by hand).
template <class R, class Visit> void visit_run(R& r, Visit&& visit)
{
  visit("max_steps", r.max_steps);
  visit("frame_every", r.frame_every);
  visit("stop_when_separated", r.stop_when_separated);
  visit("stop_after_turn_deg", degrees(r.stop_after_turn_rad));
}

/// Every settings table of a tear scene: visit_table(name, settings, visit_fields).
template <class S, class VisitTable> void visit_tear_tables(S& s, VisitTable&& visit_table)
{
  visit_table("material", s.material, [](auto& p, auto&& v) { visit_membrane_material(p, v); });
  visit_table("tearing", s.tearing, [](auto& p, auto&& v) { visit_tearing(p, v); });
  visit_table("solver", s.solver, [](auto& p, auto&& v) { visit_membrane_solver(p, v); });
  visit_table("run", s.run, [](auto& p, auto&& v) { visit_run(p, v); });
}

} // namespace ligsim::membrane
