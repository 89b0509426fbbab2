#include "pipeline/reports/knee_reports.hpp"

#include "common/run_summary.hpp"

namespace ligsim::reports {

namespace {

nlohmann::json gaps_json(const std::vector<sim::KneeContact::Gaps>& gaps)
{
  nlohmann::json json = nlohmann::json::object();
  for (const sim::KneeContact::Gaps& g : gaps)
    json[g.bone] = {{"min_gap_mm", g.min_gap_mm},
                    {"nodes_inside", g.inside},
                    {"nodes_within_d_hat", g.within_d_hat}};
  return json;
}

nlohmann::json pair_json(const sim::LigamentPair& pair, double angle_deg)
{
  return {{"angle_deg", angle_deg},
          {"first", pair.first},
          {"second", pair.second},
          {"closest_mm", pair.closest_mm},
          {"nodes_inside", pair.nodes_inside},
          {"deepest_mm", pair.deepest_mm}};
}

} // namespace

nlohmann::json to_json(const sim::OverlapReport& report)
{
  nlohmann::json json = {{"pushed", report.pushed}, {"before", gaps_json(report.before)}};
  if (report.pushed)
    json.update(
        {{"after", gaps_json(report.after)},
         {"start_offsets_mm", report.start_offsets_mm},
         {"max_node_move_mm", report.max_node_move_mm},
         {"mean_move_of_nodes_inside_mm", report.mean_surface_move_mm},
         {"newton_iterations", report.newton_iterations},
         {"method", report.reshaped ? "bones held at rest and grown from shrunk back to their "
                                      "surfaces while the ligament without in-situ strain "
                                      "settles (contact barrier); the pushed shape is the "
                                      "stress-free rest shape"
                                    : "bones held at rest and grown from shrunk back to their "
                                      "surfaces while the ligament settles (contact barrier)"},
         {"reshaped", report.reshaped}});
  return json;
}

nlohmann::json to_json(const sim::FreeFemurResult& found, const sim::JointCoordinateSystem& jcs)
{
  nlohmann::json angles = nlohmann::json::array();
  for (const sim::FreeAngle& at : found.angles) {
    const auto [ma, mm] = sim::on_tibia(at.articular.medial_centre_mm, jcs);
    const auto [la, lm] = sim::on_tibia(at.articular.lateral_centre_mm, jcs);
    nlohmann::json forces = nlohmann::json::array();
    for (const Eigen::Vector3d& f : at.ligament_femur_forces_n)
      forces.push_back(json_vector3(f));
    angles.push_back({{"angle_deg", at.angle_deg},
                      {"converged", at.converged},
                      {"iterations", at.iterations},
                      {"varus_deg", at.pose.varus_deg},
                      {"internal_rotation_deg", at.pose.internal_rotation_deg},
                      {"anterior_mm", at.pose.anterior_mm},
                      {"medial_mm", -at.pose.lateral_mm},
                      {"proximal_mm", at.pose.proximal_mm},
                      {"medial_contact_force_n", at.articular.medial_force_n.norm()},
                      {"lateral_contact_force_n", at.articular.lateral_force_n.norm()},
                      {"medial_contact_mm", {{"anterior", ma}, {"medial", mm}}},
                      {"lateral_contact_mm", {{"anterior", la}, {"medial", lm}}},
                      {"contact_area_mm2", at.articular.area_mm2},
                      {"max_contact_pressure_mpa", at.articular.max_pressure_mpa},
                      {"residual_force_n", at.residual_force_n},
                      {"residual_moment_nmm", at.residual_moment_nmm},
                      {"force_scale_n", at.force_scale_n},
                      {"ligament_femur_forces_n", forces},
                      {"wall_s", at.wall_s}});
  }
  return {{"success", found.success}, {"failure", found.failure}, {"angles", angles}};
}

nlohmann::json to_json(const std::vector<sim::PairAtAngle>& pairs)
{
  nlohmann::json json = nlohmann::json::array();
  for (const sim::PairAtAngle& at : pairs)
    json.push_back(pair_json(at.pair, at.angle_deg));
  return json;
}

nlohmann::json thickness_json(const sim::LigamentThickness& thickness, const std::string& ligament)
{
  nlohmann::json json = {{"volume_mm3", thickness.volume_mm3},
                         {"centerline_mm", thickness.centerline_mm},
                         {"mean_cross_section_mm2", thickness.mean_cross_section_mm2}};
  if (const auto published = sim::published_cross_section(ligament))
    json["published_cross_section_mm2"] = {{"mm2", published->mm2}, {"source", published->source}};
  if (const auto finding = sim::thin_ligament_finding(ligament, thickness))
    json["finding"] = *finding;
  return json;
}

nlohmann::json footprints_json(const std::vector<sim::Footprint>& prints,
                               const std::string& ligament)
{
  nlohmann::json json = nlohmann::json::object();
  for (const sim::Footprint& print : prints) {
    nlohmann::json& entry = json[print.bone];
    entry = {{"nodes", print.nodes},
             {"area_mm2", print.area_mm2},
             {"mean_distance_to_flexion_axis_mm", print.mean_axis_distance_mm},
             {"max_distance_to_flexion_axis_mm", print.max_axis_distance_mm}};
    if (const auto published = sim::published_footprint_area(ligament, print.bone))
      entry["published_area_mm2"] = {
          {"mean", published->mean_mm2}, {"sd", published->sd_mm2}, {"source", published->source}};
  }
  return json;
}

nlohmann::json to_json(const sim::CompanionSweep& companion)
{
  nlohmann::json json = {{"companion", companion.folder.string()}, {"swept", companion.swept}};
  if (companion.swept)
    json.update({{"tets", companion.tets},
                 {"size_ratio", companion.size_ratio},
                 {"wall_s", companion.wall_s},
                 {"angles_estimated", companion.angles_reached},
                 {"method", "Roache's grid convergence index, Fs |f - f_companion| / (r^p - 1) "
                            "with Fs = 3, p = 2 and r the size ratio (J Fluids Eng "
                            "1994;116:405)"}});
  if (!companion.note.empty())
    json["note"] = companion.note;
  return json;
}

nlohmann::json to_json(const sim::AngleResult& angle)
{
  const Eigen::Vector3d femur_net = sim::femur_net_force(angle);
  nlohmann::json entry = {{"angle_deg", angle.angle_deg},
                          {"converged", angle.converged},
                          {"strain_energy_mj", angle.strain_energy_mj},
                          {"max_fiber_stretch", angle.max_fiber_stretch},
                          {"mean_fiber_stretch", angle.mean_fiber_stretch},
                          {"max_fiber_strain", angle.max_fiber_stretch - 1.0},
                          {"mean_fiber_strain", angle.mean_fiber_stretch - 1.0},
                          {"volume_beyond_failure_strain", angle.failed_volume_fraction},
                          {"femur_force_n", json_vector3(angle.femur_force_n)},
                          {"femur_force_magnitude_n", angle.femur_force_n.norm()},
                          {"femur_net_force_n", json_vector3(femur_net)},
                          {"femur_net_force_magnitude_n", femur_net.norm()},
                          {"tibia_force_n", json_vector3(angle.tibia_force_n)},
                          {"tibia_force_magnitude_n", angle.tibia_force_n.norm()},
                          {"newton_iterations", angle.newton_iterations},
                          {"substeps", angle.substeps},
                          {"shifted_iterations", angle.shifted_iterations},
                          {"relative_residual", angle.relative_residual},
                          {"min_j", angle.min_j},
                          {"wall_s", angle.wall_s}};
  if (angle.frame >= 0)
    entry["frame"] = angle.frame;
  if (!std::isnan(angle.time_s))
    entry["time_s"] = angle.time_s;
  if (!std::isnan(angle.max_regional_fiber_stretch))
    entry["max_regional_fiber_strain"] = angle.max_regional_fiber_stretch - 1.0;
  if (!std::isnan(angle.error.femur_force_n))
    entry["femur_force_error_n"] = angle.error.femur_force_n;
  if (!std::isnan(angle.error.regional_fiber_strain))
    entry["max_regional_fiber_strain_error"] = angle.error.regional_fiber_strain;
  if (!std::isnan(angle.length_mm))
    entry.update({{"length_mm", angle.length_mm},
                  {"length_change_mm", angle.length_change_mm},
                  {"length_change_pct", angle.length_change_pct}});
  if (!angle.contact.empty()) {
    nlohmann::json bones = nlohmann::json::object();
    for (const sim::BoneContact& bone : angle.contact) {
      bones[bone.bone] = {{"min_gap_mm", bone.min_gap_mm}, {"penetration_mm", bone.penetration_mm}};
      if (bone.in_solve)
        bones[bone.bone].update({{"force_n", json_vector3(bone.force_n)},
                                 {"force_magnitude_n", bone.force_n.norm()},
                                 {"area_mm2", bone.area_mm2},
                                 {"nodes", bone.nodes}});
    }
    entry["contact"] = bones;
  }
  return entry;
}

nlohmann::json to_json(const sim::LigamentSetup& setup)
{
  nlohmann::json contact = {{"surface_nodes", setup.contact.surface_nodes},
                            {"voxel_mm", setup.contact.voxel_mm},
                            {"band_mm", setup.contact.band_mm}};
  for (const sim::ContactGridFigures& bone : setup.contact.bones)
    contact[bone.bone] = {{"cache", bone.cache.string()},
                          {"reused", bone.grid.reused},
                          {"build_s", bone.grid.build_s},
                          {"active_voxels", bone.grid.active_voxels},
                          {"memory_mib", bone.grid.memory_bytes / 1048576.0},
                          {"triangles", bone.triangles},
                          {"open_edges", bone.open_edges}};
  return {{"nodes", setup.nodes},
          {"tets", setup.tets},
          {"femur_nodes", setup.femur_nodes},
          {setup.distal_bone + "_nodes", setup.distal_nodes},
          {"rest_volume_mm3", setup.rest_volume_mm3},
          {"contact", contact}};
}

nlohmann::json to_json(const std::vector<sim::AngleWarning>& warnings)
{
  nlohmann::json json = nlohmann::json::array();
  for (const sim::AngleWarning& warning : warnings)
    json.push_back({{"angle_deg", warning.angle_deg}, {"warning", warning.warning}});
  return json;
}

nlohmann::json to_json(const sim::AxisFigures& figures)
{
  if (const auto* points = std::get_if<sim::AxisPoints>(&figures))
    return {{"first_mm", json_vector3(points->first_mm)},
            {"second_mm", json_vector3(points->second_mm)}};
  if (const auto* fit = std::get_if<sim::CondyleFitFigures>(&figures))
    return {{"radius_mm", fit->radius_mm},
            {"rms_residual_mm", fit->rms_residual_mm},
            {"span_mm", fit->span_mm},
            {"points_used", fit->points_used},
            {"points_considered", fit->points_considered},
            {"proximal", json_vector3(fit->proximal)},
            {"posterior_hint", json_vector3(fit->posterior_hint)}};
  const auto& epicondyles = std::get<sim::EpicondylarFigures>(figures);
  return {{"medial_epicondyle_mm", json_vector3(epicondyles.medial_epicondyle_mm)},
          {"lateral_epicondyle_mm", json_vector3(epicondyles.lateral_epicondyle_mm)},
          {"length_mm", epicondyles.length_mm},
          {"oriented", epicondyles.oriented}};
}

nlohmann::json to_json(const sim::MotionFigures& figures)
{
  nlohmann::json json;
  if (const std::optional<sim::OtherAxis>& other = figures.other_axis) {
    nlohmann::json& entry = json["other_axis"];
    entry["method"] = other->method;
    if (other->found) {
      entry["direction"] = json_vector3(other->found->axis.direction);
      entry["point_mm"] = json_vector3(other->found->axis.point_mm);
      entry["angle_deg"] = other->angle_deg;
      entry["figures"] = to_json(other->found->figures);
    } else {
      entry["not_available"] = other->not_available;
    }
  }
  const sim::TibialAxisFigures& tibial = figures.tibial_axis;
  json["tibial_axis"] = {{"source", tibial.source}, {"direction", json_vector3(tibial.direction)}};
  if (tibial.angle_to_proximal_deg)
    json["tibial_axis"]["angle_to_proximal_deg"] = *tibial.angle_to_proximal_deg;
  const sim::BuiltPose& built = figures.built_pose;
  if (built.flexion_deg)
    json["built_pose"] = {{"flexion_deg", *built.flexion_deg},
                          {"femoral_shaft", json_vector3(built.femoral_shaft)},
                          {"source", built.source},
                          {"note", "the angles swept are counted from the built pose"}};
  else
    json["built_pose"] = {{"not_measured", built.not_measured}};
  json["side"] = figures.side;
  json["frame_source"] = figures.frame_source;
  json["path"] = figures.path;
  if (!figures.note.empty())
    json["note"] = figures.note;
  return json;
}

} // namespace ligsim::reports
