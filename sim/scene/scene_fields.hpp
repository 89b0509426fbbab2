#pragma once
/// @brief A scene's keys that are settings, listed once per table: the reader (scene_file.cpp)
/// and the writer of summary.json's `parameters.config` both walk them. Each visit_*(s, visit)
/// calls visit(key, member) or visit(key, choice(...)); `s` may be const (writing) or not
/// (reading). The mesh, the node sets, the constraints, the loads and the bones are read by hand
/// in scene_file.cpp: they are lists of their own, not settings.

#include "common/config_choice.hpp"
#include "sim/material/material_fields.hpp"
#include "sim/scene/contact_table.hpp"
#include "sim/scene/scene.hpp"
#include "sim/solver/newton_fields.hpp"

#include <string>

namespace ligsim::sim {

/// [solver] kind's text.
inline std::string to_string(SceneKind kind)
{
  return kind == SceneKind::quasi_static ? "static" : "dynamic";
}

/// [solver]: the kind, the load steps, the Newton iteration (as a flexion config's [static]) and
/// the linear solves.
template <class S, class Visit> void visit_scene_solver(S& s, Visit&& visit)
{
  visit("kind", choice(s.kind, to_string, {SceneKind::quasi_static, SceneKind::dynamic}));
  visit("load_steps", s.newton.load_steps);
  visit_newton_iteration(s.newton, visit);
  visit("energy_tolerance", s.newton.energy_tolerance);
  visit("pcg_tolerance", s.newton.pcg.tolerance);
  visit("pcg_max_iterations", s.newton.pcg.max_iterations);
  visit("psd_projection",
        choice(s.newton.projection, to_string,
               {PsdProjection::automatic, PsdProjection::always, PsdProjection::never}));
}

/// [dynamics]: implicit Euler's frames, inertia and damping.
template <class D, class Visit> void visit_scene_dynamics(D& d, Visit&& visit)
{
  visit("time_step_s", d.time_step_s);
  visit("frames", d.frames);
  visit("until_converged", d.until_converged);
  visit("convergence_tolerance", d.convergence_tolerance);
  visit("ramp_frames", d.ramp_frames);
  visit("density_kg_m3", d.density_kg_m3);
  visit("mass_damping_per_s", d.mass_damping_per_s);
  visit("stiffness_damping_s", d.stiffness_damping_s);
  visit("max_halvings", d.max_halvings);
}

template <class O, class Visit> void visit_scene_output(O& o, Visit&& visit)
{
  visit("every", o.every);
  visit("vtu", o.vtu);
}

/// Every settings table of a scene: visit_table(name, settings, visit_fields). [fibers] is
/// visited where the material has fibers.
template <class S, class VisitTable> void visit_scene_tables(S& s, VisitTable&& visit_table)
{
  visit_table("material", s.material, [](auto& p, auto&& v) { visit_ground_substance(p, v); });
  if (s.material.fiber)
    visit_table("fibers", *s.material.fiber, [](auto& p, auto&& v) { visit_fiber_law(p, v); });
  visit_table("solver", s, [](auto& p, auto&& v) { visit_scene_solver(p, v); });
  if (s.kind == SceneKind::dynamic)
    visit_table("dynamics", s.dynamics, [](auto& p, auto&& v) { visit_scene_dynamics(p, v); });
  visit_table("output", s.output, [](auto& p, auto&& v) { visit_scene_output(p, v); });
  if (!s.bones.empty())
    visit_table("contact", s.contact, [](auto& p, auto&& v) { visit_contact(p, v); });
}

} // namespace ligsim::sim
