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

} // namespace ligsim::reports
