#include "stages/attachments/attachments.hpp"

#include "common/error.hpp"
#include "stages/geometry/surface_query.hpp"
#include "stages/geometry/surface_topology.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <tuple>

namespace ligsim::attachments {

namespace {

enum class Bone { femur, tibia };

const char* name_of(Bone bone)
{
  return bone == Bone::femur ? "femoral" : "tibial";
}

std::string resolved_rule(const Rule& rule, const Inputs& inputs, Bone bone)
{
  if (rule.rule != "auto")
    return rule.rule;
  if (!rule.indices.empty())
    return "indices";
  if (!rule.array.empty())
    return "array";
  const TriangleSurface* surface = bone == Bone::femur ? inputs.femur : inputs.tibia;
  return surface ? "proximity" : "end";
}

Area from_indices(const Rule& rule, const Inputs& inputs, Bone bone)
{
  const auto count = static_cast<int>(inputs.ligament->V.rows());
  for (int v : rule.indices)
    if (v < 0 || v >= count)
      fail("{} attachment: vertex index {} is out of range (the surface has {} vertices)",
           name_of(bone), v, count);
  Area area;
  area.vertices = rule.indices;
  area.rule = fmt::format("indices ({} given)", rule.indices.size());
  return area;
}

Area from_array(const Rule& rule, const Inputs& inputs, Bone bone)
{
  const auto found = inputs.arrays.find(rule.array);
  if (found == inputs.arrays.end())
    fail("{} attachment: the ligament surface has no point-data array '{}'", name_of(bone),
         rule.array);
  Area area;
  for (Eigen::Index v = 0; v < found->second.size(); ++v)
    if (found->second[v] != 0.0)
      area.vertices.push_back(static_cast<int>(v));
  area.rule = fmt::format("array '{}' non-zero", rule.array);
  return area;
}

Area from_proximity(const Rule& rule, const Inputs& inputs, Bone bone)
{
  const TriangleSurface* surface = bone == Bone::femur ? inputs.femur : inputs.tibia;
  if (surface == nullptr)
    fail("{} attachment: rule 'proximity' needs the {} surface", name_of(bone),
         bone == Bone::femur ? "femur" : "tibia");
  if (!(rule.distance_mm > 0.0))
    fail("{} attachment: proximity distance must be positive, got {} mm", name_of(bone),
         rule.distance_mm);
  const SurfaceQuery query(*surface);
  // A ligament segmented into its bone is attached there however deep it goes (the HRA male
  // LCL enters the fibular head by 3 mm); only a closed bone has an inside to ask about.
  const bool closed = check_topology(*surface).closed_manifold();
  Area area;
  int inside = 0;
  for (Eigen::Index v = 0; v < inputs.ligament->V.rows(); ++v) {
    const Eigen::Vector3d p = inputs.ligament->V.row(v).transpose();
    const bool near = query.distance(p) <= rule.distance_mm;
    const bool in = !near && closed && query.inside(p);
    if (near || in)
      area.vertices.push_back(static_cast<int>(v));
    inside += in;
  }
  area.rule = fmt::format("proximity: within {} mm of the {}", rule.distance_mm,
                          bone == Bone::femur ? "femur" : "tibia");
  if (inside > 0)
    area.corrections.push_back(fmt::format(
        "{} vertices deeper than {} mm inside the bone taken too", inside, rule.distance_mm));
  return area;
}

Area from_patch(const Rule& rule, const Inputs& inputs, Bone bone)
{
  const TriangleSurface* patch = bone == Bone::femur ? inputs.femur_patch : inputs.tibia_patch;
  if (patch == nullptr || patch->F.rows() == 0)
    fail("{} attachment: rule 'patch' needs the footprint surface (`patch`)", name_of(bone));
  if (!(rule.distance_mm > 0.0))
    fail("{} attachment: patch distance must be positive, got {} mm", name_of(bone),
         rule.distance_mm);
  const SurfaceQuery query(*patch);
  Area area;
  for (Eigen::Index v = 0; v < inputs.ligament->V.rows(); ++v)
    if (query.distance(inputs.ligament->V.row(v).transpose()) <= rule.distance_mm)
      area.vertices.push_back(static_cast<int>(v));
  area.rule = fmt::format("patch: within {} mm of {}", rule.distance_mm,
                          rule.patch.empty() ? "the footprint surface" : rule.patch);
  return area;
}

Area from_end(const Rule& rule, const Inputs& inputs, Bone bone, const Area* other)
{
  if (!(rule.end_length_mm > 0.0))
    fail("{} attachment: end length must be positive, got {} mm", name_of(bone),
         rule.end_length_mm);
  const Points& V = inputs.ligament->V;
  const Eigen::Vector3d axis = main_axis(V);
  const Eigen::VectorXd s = V * axis;
  const double lo = s.minCoeff(), hi = s.maxCoeff();
  bool at_max;
  std::string why;
  std::string end = rule.end;
  if (end == "auto" && inputs.proximal)
    end = bone == Bone::femur ? "proximal" : "distal";
  if (end == "proximal" || end == "distal") {
    if (!inputs.proximal)
      fail("{} attachment: end '{}' needs the knee's proximal direction ([anatomy] proximal, a "
           "label map's frame, or both bones)",
           name_of(bone), end);
    at_max = (axis.dot(*inputs.proximal) > 0.0) == (end == "proximal");
    why = end + " end";
  } else if (end == "min" || end == "max") {
    at_max = end == "max";
    why = end;
  } else if (end != "auto") {
    fail("{} attachment: end must be 'proximal', 'distal', 'min', 'max' or 'auto', got '{}'",
         name_of(bone), end);
  } else if (other != nullptr && !other->vertices.empty()) {
    const double other_s = other->mean.dot(axis);
    at_max = (hi - other_s) > (other_s - lo);
    why = "farther from the other attachment";
  } else {
    at_max = bone == Bone::femur;
    why = bone == Bone::femur ? "proximal (+z) end" : "distal (-z) end";
  }
  Area area;
  for (Eigen::Index v = 0; v < V.rows(); ++v)
    if (at_max ? s[v] >= hi - rule.end_length_mm : s[v] <= lo + rule.end_length_mm)
      area.vertices.push_back(static_cast<int>(v));
  area.rule =
      fmt::format("end: within {} mm of the {} end along the main axis ({:.3f}, {:.3f}, "
                  "{:.3f}), {}",
                  rule.end_length_mm, at_max ? "max" : "min", axis.x(), axis.y(), axis.z(), why);
  return area;
}

/// The landmark a rule names, if the anatomy has it (a given point otherwise).
std::optional<Eigen::Vector3d> landmark_point(const Rule& rule, const Inputs& inputs, Bone bone)
{
  if (rule.landmark.empty())
    return rule.point_mm.allFinite() ? std::optional(rule.point_mm) : std::nullopt;
  const auto found = inputs.landmarks.find(rule.landmark);
  if (found != inputs.landmarks.end())
    return found->second;
  if (rule.snap)
    return std::nullopt;
  std::string known;
  for (const auto& [name, point] : inputs.landmarks)
    known += (known.empty() ? "" : ", ") + name;
  fail("{} attachment: no landmark '{}' in the anatomy (known: {})", name_of(bone), rule.landmark,
       known.empty() ? "none" : known);
}

/// The ligament's end toward `bone`, `length_mm` long.
Area end_toward(const Rule& rule, const Inputs& inputs, Bone bone, double length_mm)
{
  Rule end = rule;
  end.end = !inputs.proximal ? "auto" : bone == Bone::femur ? "proximal" : "distal";
  end.end_length_mm = length_mm;
  return from_end(end, inputs, bone, nullptr);
}

/// The ligament's vertices within `radius_mm` of `centre`.
std::vector<int> disc(const Inputs& inputs, const Eigen::Vector3d& centre, double radius_mm)
{
  std::vector<int> vertices;
  for (Eigen::Index v = 0; v < inputs.ligament->V.rows(); ++v)
    if ((inputs.ligament->V.row(v).transpose() - centre).norm() <= radius_mm)
      vertices.push_back(static_cast<int>(v));
  return vertices;
}

Area from_landmark(const Rule& rule, const Inputs& inputs, Bone bone)
{
  if (!(rule.radius_mm > 0.0))
    fail("{} attachment: landmark radius must be positive, got {} mm", name_of(bone),
         rule.radius_mm);
  const std::optional<Eigen::Vector3d> landmark = landmark_point(rule, inputs, bone);
  if (!landmark && rule.landmark.empty())
    fail("{} attachment: rule 'landmark' needs `landmark` (a name) or `point_mm`", name_of(bone));
  if (!landmark) { // snap: the anatomy could not find it
    Area area = end_toward(rule, inputs, bone, rule.radius_mm);
    area.corrections.push_back(fmt::format(
        "the anatomy has no {}: the footprint is the ligament's end toward the bone instead",
        rule.landmark));
    return area;
  }
  Eigen::Vector3d centre = *landmark;
  std::string what = rule.landmark.empty() ? "the given point" : "landmark " + rule.landmark;
  for (const auto& [offset, direction, name] :
       {std::tuple{rule.proximal_mm, inputs.proximal, "proximal"},
        std::tuple{rule.posterior_mm, inputs.posterior, "posterior"}}) {
    if (offset == 0.0)
      continue;
    if (!direction)
      fail("{} attachment: an offset {} of the landmark needs the knee's {} direction ([anatomy] "
           "{}, or a label map's frame)",
           name_of(bone), name, name, name);
    centre += offset * *direction;
    what += fmt::format(" moved {} mm {}", offset, name);
  }
  Area area;
  area.vertices = disc(inputs, centre, rule.radius_mm);
  if (area.vertices.empty() && rule.snap) {
    const Area end = end_toward(rule, inputs, bone, 3.0 * rule.radius_mm);
    int nearest = end.vertices.front();
    for (int v : end.vertices)
      if ((inputs.ligament->V.row(v).transpose() - centre).norm() <
          (inputs.ligament->V.row(nearest).transpose() - centre).norm())
        nearest = v;
    const Eigen::Vector3d snapped = inputs.ligament->V.row(nearest).transpose();
    area.corrections.push_back(
        fmt::format("snapped: {} ({:.2f}, {:.2f}, {:.2f}) missed the ligament by {:.1f} mm; the "
                    "disc is centred on the ligament's nearest point at its end toward the bone",
                    what, centre.x(), centre.y(), centre.z(), (snapped - centre).norm()));
    centre = snapped;
    what = "the snapped point";
    area.vertices = disc(inputs, centre, rule.radius_mm);
  }
  area.rule = fmt::format("landmark: within {} mm of {} ({:.2f}, {:.2f}, {:.2f})", rule.radius_mm,
                          what, centre.x(), centre.y(), centre.z());
  return area;
}

/// Keeps the vertices within `rule.bone_distance_mm` of the bone, when both are given.
void keep_next_to_bone(Area& area, const Rule& rule, const Inputs& inputs, Bone bone)
{
  const TriangleSurface* surface = bone == Bone::femur ? inputs.femur : inputs.tibia;
  if (!(rule.bone_distance_mm > 0.0) || surface == nullptr)
    return;
  const SurfaceQuery query(*surface);
  std::vector<int> kept;
  for (int v : area.vertices)
    if (query.distance(inputs.ligament->V.row(v).transpose()) <= rule.bone_distance_mm)
      kept.push_back(v);
  area.vertices = std::move(kept);
  area.rule += fmt::format(", within {} mm of the {}", rule.bone_distance_mm,
                           bone == Bone::femur ? "femur" : "tibia");
}

void finish(Area& area, const TriangleSurface& ligament, Bone bone)
{
  std::sort(area.vertices.begin(), area.vertices.end());
  area.vertices.erase(std::unique(area.vertices.begin(), area.vertices.end()), area.vertices.end());
  if (area.vertices.empty())
    fail("{} attachment area is empty (rule {})", name_of(bone), area.rule);
  area.mean.setZero();
  for (int v : area.vertices)
    area.mean += ligament.V.row(v).transpose();
  area.mean /= static_cast<double>(area.vertices.size());
  std::vector<char> in(static_cast<std::size_t>(ligament.V.rows()), 0);
  for (int v : area.vertices)
    in[static_cast<std::size_t>(v)] = 1;
  area.area_mm2 = 0.0;
  for (Eigen::Index f = 0; f < ligament.F.rows(); ++f) {
    int corners = 0;
    for (int k = 0; k < 3; ++k)
      corners += in[static_cast<std::size_t>(ligament.F(f, k))];
    if (corners == 0)
      continue;
    const Eigen::Vector3d a = ligament.V.row(ligament.F(f, 0));
    const Eigen::Vector3d b = ligament.V.row(ligament.F(f, 1));
    const Eigen::Vector3d c = ligament.V.row(ligament.F(f, 2));
    area.area_mm2 += corners / 3.0 * 0.5 * (b - a).cross(c - a).norm();
  }
  area.extent_mm = 0.0;
  for (std::size_t i = 0; i < area.vertices.size(); ++i)
    for (std::size_t j = i + 1; j < area.vertices.size(); ++j)
      area.extent_mm =
          std::max(area.extent_mm,
                   (ligament.V.row(area.vertices[i]) - ligament.V.row(area.vertices[j])).norm());
}

} // namespace

Eigen::Vector3d main_axis(const Points& points)
{
  const Eigen::RowVector3d mean = points.colwise().mean();
  const Eigen::Matrix3d covariance =
      (points.rowwise() - mean).transpose() * (points.rowwise() - mean);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  Eigen::Vector3d axis = solver.eigenvectors().col(2);
  return axis.z() < 0.0 ? Eigen::Vector3d(-axis) : axis;
}

Attachments find(const Inputs& inputs, const Rule& femur_rule, const Rule& tibia_rule)
{
  if (inputs.ligament == nullptr || inputs.ligament->V.rows() == 0)
    fail("attachments: the ligament surface is empty");
  const std::string femur_kind = resolved_rule(femur_rule, inputs, Bone::femur);
  const std::string tibia_kind = resolved_rule(tibia_rule, inputs, Bone::tibia);

  // One footprint by its rule; `other` is the other footprint, for an end rule's "auto" end.
  const auto make = [&](const std::string& kind, const Rule& rule, Bone bone,
                        const Area* other) -> Area {
    Area area;
    if (kind == "indices")
      area = from_indices(rule, inputs, bone);
    else if (kind == "array")
      area = from_array(rule, inputs, bone);
    else if (kind == "proximity")
      area = from_proximity(rule, inputs, bone);
    else if (kind == "patch")
      area = from_patch(rule, inputs, bone);
    else if (kind == "landmark")
      area = from_landmark(rule, inputs, bone);
    else if (kind == "end")
      area = from_end(rule, inputs, bone, other);
    else
      fail("{} attachment: unknown rule '{}' (use auto, indices, array, proximity, patch, "
           "landmark or end)",
           name_of(bone), kind);
    if (kind != "indices" && kind != "array")
      keep_next_to_bone(area, rule, inputs, bone);
    finish(area, *inputs.ligament, bone);
    return area;
  };
  // The footprint held to its published size and place (Rule::max_area_mm2, max_distance_mm).
  const auto held = [&](const std::string& kind, const Rule& rule, Bone bone,
                        const Area* other) -> Area {
    Area area = make(kind, rule, bone, other);
    if (rule.max_area_mm2 > 0.0 && area.area_mm2 > rule.max_area_mm2) {
      if (kind != "landmark")
        fail("{} attachment: the footprint ({}) is {:.0f} mm^2, more than the {:.0f} mm^2 its "
             "published area allows: give a rule that finds a smaller one ([attachments] rule, "
             "distance_mm or bone_distance_mm), or max_area_mm2 = 0 to accept it",
             name_of(bone), area.rule, area.area_mm2, rule.max_area_mm2);
      Rule smaller = rule;
      const double found_mm2 = area.area_mm2;
      while (area.area_mm2 > rule.max_area_mm2 && smaller.radius_mm > 1.0) {
        smaller.radius_mm *= 0.9;
        const std::vector<std::string> corrections = area.corrections;
        area = make(kind, smaller, bone, other);
        area.corrections = corrections;
      }
      area.corrections.push_back(fmt::format(
          "the disc's radius shrunk from {} to {:.2f} mm: the footprint was {:.0f} mm^2, more "
          "than the {:.0f} mm^2 its published area allows; now {:.0f} mm^2",
          rule.radius_mm, smaller.radius_mm, found_mm2, rule.max_area_mm2, area.area_mm2));
    }
    if (rule.max_distance_mm > 0.0 && kind == "landmark")
      if (const auto landmark = landmark_point(rule, inputs, bone)) {
        const double distance = (area.mean - *landmark).norm();
        if (distance > rule.max_distance_mm)
          fail("{} attachment: the footprint found ({}; {}) lies {:.1f} mm from {}, farther than "
               "the {:.1f} mm its published place allows: the ligament's end does not reach its "
               "landmark. Check the ligament's and the bone's segmentation, or give the "
               "footprint ([attachments] rule = \"landmark\" with point_mm, or another rule)",
               name_of(bone), area.rule,
               area.corrections.empty() ? "as found" : area.corrections.back(), distance,
               rule.landmark.empty() ? "its point" : rule.landmark, rule.max_distance_mm);
      }
    return area;
  };

  // End rules last: "auto" ends look away from the other area when it is known.
  std::optional<Area> femur, tibia;
  if (femur_kind != "end")
    femur = held(femur_kind, femur_rule, Bone::femur, nullptr);
  if (tibia_kind != "end")
    tibia = held(tibia_kind, tibia_rule, Bone::tibia, nullptr);
  if (!tibia)
    tibia = held(tibia_kind, tibia_rule, Bone::tibia, femur ? &*femur : nullptr);
  if (!femur)
    femur = held(femur_kind, femur_rule, Bone::femur, &*tibia);

  std::vector<int> shared;
  std::set_intersection(femur->vertices.begin(), femur->vertices.end(), tibia->vertices.begin(),
                        tibia->vertices.end(), std::back_inserter(shared));
  if (!shared.empty()) {
    const Eigen::Vector3d p = inputs.ligament->V.row(shared.front());
    fail("the femoral and tibial attachment areas overlap in {} vertices (first: vertex {} at "
         "({:.2f}, {:.2f}, {:.2f}) mm)",
         shared.size(), shared.front(), p.x(), p.y(), p.z());
  }
  Attachments result;
  result.femur = std::move(*femur);
  result.tibia = std::move(*tibia);
  return result;
}

} // namespace ligsim::attachments
