#include "sim/flexion/plausibility.hpp"

#include "sim/contact/contact_surface.hpp"
#include "sim/flexion/knee_flexion.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace ligsim::sim {

namespace {

double axis_distance(const Eigen::Vector3d& p, const FlexionAxis& axis)
{
  const Eigen::Vector3d w = p - axis.point_mm;
  const Eigen::Vector3d u = axis.direction.normalized();
  return (w - w.dot(u) * u).norm();
}

Footprint footprint_of(const TetMesh& mesh, const ContactSurface& boundary,
                       const std::vector<int>& nodes, const std::string& bone,
                       const FlexionAxis& axis)
{
  Footprint print;
  print.bone = bone;
  print.nodes = static_cast<int>(nodes.size());
  std::vector<bool> bound(static_cast<std::size_t>(mesh.V.rows()), false);
  for (int n : nodes) {
    bound[static_cast<std::size_t>(n)] = true;
    const double d = axis_distance(mesh.V.row(n).transpose(), axis);
    print.mean_axis_distance_mm += d / static_cast<double>(nodes.size());
    print.max_axis_distance_mm = std::max(print.max_axis_distance_mm, d);
  }
  for (Eigen::Index f = 0; f < boundary.faces.rows(); ++f) {
    if (!bound[static_cast<std::size_t>(boundary.faces(f, 0))] ||
        !bound[static_cast<std::size_t>(boundary.faces(f, 1))] ||
        !bound[static_cast<std::size_t>(boundary.faces(f, 2))])
      continue;
    const Eigen::Vector3d a = mesh.V.row(boundary.faces(f, 0));
    const Eigen::Vector3d b = mesh.V.row(boundary.faces(f, 1));
    const Eigen::Vector3d c = mesh.V.row(boundary.faces(f, 2));
    print.area_mm2 += 0.5 * (b - a).cross(c - a).norm();
  }
  return print;
}

} // namespace

std::optional<PublishedArea> published_footprint_area(const std::string& ligament,
                                                      const std::string& bone)
{
  // Superficial MCL: Liu et al., J Orthop Surg Res 2010 (with LaPrade et al., J Bone Joint Surg
  // Am 2007;89:2000 for the positions). LCL: LaPrade et al., Am J Sports Med 2003;31:854.
  if (ligament == "MCL")
    return bone == "femur" ? PublishedArea{79.7, 17.6, "Liu et al. 2010 (superficial MCL)"}
                           : PublishedArea{348.6, 42.8, "Liu et al. 2010 (superficial MCL)"};
  if (ligament == "LCL")
    return bone == "femur" ? PublishedArea{48.0, 0.0, "LaPrade et al. 2003 (range 43-52)"}
                           : PublishedArea{43.0, 0.0, "LaPrade et al. 2003 (range 39-50)"};
  // ACL: Araki et al., Knee Surg Sports Traumatol Arthrosc 2017.
  if (ligament == "ACL")
    return bone == "femur" ? PublishedArea{109.7, 10.9, "Araki et al. 2017 (ACL)"}
                           : PublishedArea{135.2, 15.1, "Araki et al. 2017 (ACL)"};
  return std::nullopt;
}

std::optional<PublishedCrossSection> published_cross_section(const std::string& ligament)
{
  // ACL: 20 cadaver knees, callipers at mid-substance (Siebold et al., Knee Surg Sports Traumatol
  // Arthrosc 2015;23:3136). PCL: 1.5 times the ACL's at mid-substance within the same knees
  // (Harner et al., J Orthop Res 1995;13:429). LCL: LaPrade et al., Am J Sports Med 2005.
  if (ligament == "ACL")
    return PublishedCrossSection{38.7, "Siebold et al. 2015, at mid-substance"};
  if (ligament == "PCL")
    return PublishedCrossSection{58.0, "1.5 times the ACL's 38.7, Harner et al. 1995"};
  if (ligament == "LCL")
    return PublishedCrossSection{11.9, "LaPrade et al. 2005"};
  return std::nullopt;
}

std::optional<LigamentThickness> ligament_thickness(const TetMesh& mesh, const Points& centerline)
{
  if (centerline.rows() < 2)
    return std::nullopt;
  LigamentThickness thickness;
  for (Eigen::Index t = 0; t < mesh.T.rows(); ++t) {
    const Eigen::Vector3d a = mesh.V.row(mesh.T(t, 0));
    const Eigen::Vector3d b = mesh.V.row(mesh.T(t, 1));
    const Eigen::Vector3d c = mesh.V.row(mesh.T(t, 2));
    const Eigen::Vector3d d = mesh.V.row(mesh.T(t, 3));
    thickness.volume_mm3 += std::abs((b - a).dot((c - a).cross(d - a))) / 6.0;
  }
  for (Eigen::Index p = 1; p < centerline.rows(); ++p)
    thickness.centerline_mm += (centerline.row(p) - centerline.row(p - 1)).norm();
  if (thickness.centerline_mm > 0.0)
    thickness.mean_cross_section_mm2 = thickness.volume_mm3 / thickness.centerline_mm;
  return thickness;
}

std::optional<std::string> thin_ligament_finding(const std::string& ligament,
                                                 const LigamentThickness& thickness)
{
  const auto published = published_cross_section(ligament);
  if (!published || !(thickness.mean_cross_section_mm2 > 0.0) ||
      thickness.mean_cross_section_mm2 * 3.0 > published->mm2)
    return std::nullopt;
  return fmt::format("the {} as built is {:.1f} mm^2 in mean cross-section ({:.0f} mm^3 over its "
                     "{:.1f} mm centerline), {:.1f} times under the published {:g} mm^2 ({}): its "
                     "stiffness and forces are as much too small, and the knee's path leans on "
                     "the other structures where the real one would hold it",
                     ligament, thickness.mean_cross_section_mm2, thickness.volume_mm3,
                     thickness.centerline_mm, published->mm2 / thickness.mean_cross_section_mm2,
                     published->mm2, published->source);
}

std::vector<Footprint> footprints(const KneeModel& model, const FlexionAxis& axis)
{
  const ContactSurface boundary = boundary_surface(model.mesh);
  return {footprint_of(model.mesh, boundary, model.femur_nodes, "femur", axis),
          footprint_of(model.mesh, boundary, model.tibia_nodes, model.distal_bone, axis)};
}

std::vector<std::string> plausibility_warnings(const AngleResult& angle,
                                               const PlausibilityContext& context)
{
  const LigamentSettings& ligament = context.ligament;
  std::vector<std::string> causes;
  for (const Footprint& print : context.footprints)
    if (print.bone == "femur" && print.max_axis_distance_mm > 10.0)
      causes.push_back(fmt::format("the femoral footprint reaches {:.1f} mm from the flexion axis "
                                   "(its nodes turn with the femur on that radius)",
                                   print.max_axis_distance_mm));
  if (context.in_situ_strain > 0.04)
    causes.push_back(fmt::format("an in-situ strain of {:.1f} %", 100.0 * context.in_situ_strain));
  if (context.thin)
    causes.push_back(*context.thin);
  const auto why_of = [](const std::vector<std::string>& listed) {
    return listed.empty() ? std::string()
                          : fmt::format("; likely causes: {}", fmt::join(listed, "; "));
  };
  const std::string why = why_of(causes);

  std::vector<std::string> warnings;
  if (angle.failed_volume_fraction > 0.0) {
    std::vector<std::string> strain_causes = causes;
    // Beside a footprint whose bound face turns with its bone while the band around it is free,
    // single elements pass the failure strain where no measurement scale does (docs/knee.md,
    // "The peak strain and the footprint").
    if (angle.max_regional_fiber_stretch - 1.0 <= ligament.failure_strain)
      strain_causes.insert(strain_causes.begin(),
                           fmt::format("a local peak: averaged within {:g} mm no part of the "
                                       "ligament passes the failure strain, as at the edge of a "
                                       "footprint bound to its turning bone",
                                       ligament.strain_region_radius_mm));
    warnings.push_back(fmt::format(
        "{:.2g} % of the {}'s volume is strained beyond its failure strain of {:.1f} % (max fiber "
        "strain {:.1f} % in one element, {:.1f} % averaged within {:g} mm){}",
        100.0 * angle.failed_volume_fraction, ligament.name, 100.0 * ligament.failure_strain,
        100.0 * (angle.max_fiber_stretch - 1.0), 100.0 * (angle.max_regional_fiber_stretch - 1.0),
        ligament.strain_region_radius_mm, why_of(strain_causes)));
  }
  // A bone's whole pull, footprint and contact (net_force): beside a footprint the two can
  // cancel, and the footprint's reaction alone would warn of a load the ligament does not carry.
  const std::string distal = context.footprints.size() > 1 ? context.footprints[1].bone : "tibia";
  for (const auto& [bone, force] :
       {std::pair{std::string("femur"), femur_net_force(angle)},
        std::pair{distal, net_force(angle, distal, angle.tibia_force_n)}})
    if (force.norm() > ligament.failure_load_n)
      warnings.push_back(fmt::format("the {} pulls on the {} with {:.0f} N, beyond its failure "
                                     "load of {:.0f} N{}",
                                     bone, ligament.name, force.norm(), ligament.failure_load_n,
                                     why));
  return warnings;
}

} // namespace ligsim::sim
