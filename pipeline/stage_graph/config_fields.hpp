#pragma once
/// @brief Every build parameter with its config key, listed once per section. Reading the TOML
/// file, writing summary.json and keying the stage cache all walk these lists, so none of them
/// can miss a parameter.

#include "common/config_choice.hpp"
#include "pipeline/stage_graph/build_config.hpp"
#include "sim/material/material_fields.hpp"

#include <string>
#include <type_traits>

namespace ligsim::pipeline {

// Each visit_fields(parameters, visit) calls visit(key, member) for every parameter; the
// parameters may be const (writing) or not (reading).

template <class Rule, class Visit> void visit_rule(Rule& r, Visit&& visit)
{
  visit("rule", r.rule);
  visit("indices", r.indices);
  visit("array", r.array);
  visit("distance_mm", r.distance_mm);
  visit("end_length_mm", r.end_length_mm);
  visit("end", r.end);
  visit("patch", r.patch);
  visit("landmark", r.landmark);
  visit("point_mm", r.point_mm);
  visit("radius_mm", r.radius_mm);
  visit("proximal_mm", r.proximal_mm);
  visit("posterior_mm", r.posterior_mm);
  visit("bone_distance_mm", r.bone_distance_mm);
  visit("snap", r.snap);
  visit("max_distance_mm", r.max_distance_mm);
  visit("max_area_mm2", r.max_area_mm2);
}

/// The knee's side, directions and landmarks ([anatomy]).
template <class P, class Visit> void visit_anatomy(P& p, Visit&& visit)
{
  visit("side", p.side);
  visit("proximal", p.proximal);
  visit("posterior", p.posterior);
  visit("medial_epicondyle_mm", p.medial_epicondyle_mm);
  visit("lateral_epicondyle_mm", p.lateral_epicondyle_mm);
  visit("medial_epicondyle_surface", p.medial_epicondyle_surface);
  visit("lateral_epicondyle_surface", p.lateral_epicondyle_surface);
}

template <class P, class Visit> void visit_voxelize(P& p, Visit&& visit)
{
  visit("spacing_mm", p.spacing_mm);
  visit("padding_voxels", p.padding_voxels);
  visit("max_voxels", p.max_voxels);
}

template <class P, class Visit> void visit_centerline(P& p, Visit&& visit)
{
  visit("alpha", p.alpha);
  visit("span", choice(p.span, centerline::to_string,
                       {centerline::Span::means, centerline::Span::attachments}));
  visit("refine", p.refine);
  visit("relax_iterations", p.relax_iterations);
  visit("extend_to_surface", p.extend_to_surface);
  visit("point_spacing_mm", p.point_spacing_mm);
  visit("smoothing_passes", p.smoothing_passes);
}

template <class P, class Visit> void visit_field(P& p, Visit&& visit)
{
  visit("method",
        choice(p.method, field::to_string, {field::Method::geometric, field::Method::laplace}));
  visit("laplace_tolerance", p.laplace_tolerance);
  visit("laplace_max_iterations", p.laplace_max_iterations);
}

template <class P, class Visit> void visit_tetmesh(P& p, Visit&& visit)
{
  visit("cell_size_mm", p.cell_size_mm);
  visit("facet_size_mm", p.facet_size_mm);
  visit("facet_distance_mm", p.facet_distance_mm);
  visit("facet_angle_deg", p.facet_angle_deg);
  visit("radius_edge_ratio", p.radius_edge_ratio);
  visit("exude_slivers", p.exude_slivers);
  visit("perturb", p.perturb);
  visit("seed", p.seed);
  visit("order", p.order);
  visit("footprint_rims", p.footprint_rims);
}

template <class P, class Visit> void visit_fibers(P& p, Visit&& visit)
{
  visit("samples_per_tet", p.samples_per_tet);
}

template <class P, class Visit> void visit_model(P& p, Visit&& visit)
{
  visit("in_situ_strain", p.in_situ_strain);
}

template <class P, class Visit> void visit_error_estimate(P& p, Visit&& visit)
{
  visit("mesh_scale", p.mesh_scale);
}

/// The Weiss material: the simulator's list (sim/material/material_fields.hpp), as flexion
/// configs and scenes name it.
template <class P, class Visit> void visit_material(P& p, Visit&& visit)
{
  sim::visit_weiss_material(p, visit);
}

/// Without axis_given, which the reader derives from the presence of the axis keys.
template <class P, class Visit> void visit_flexion(P& p, Visit&& visit)
{
  visit("max_angle_deg", p.max_angle_deg);
  visit("steps", p.steps);
  visit("axis_point_mm", p.axis_point_mm);
  visit("axis_direction", p.axis_direction);
}

} // namespace ligsim::pipeline
