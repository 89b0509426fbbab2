#include "stages/attachments/attachments.hpp"

#include "common/error.hpp"
#include "stages/geometry/surface_query.hpp"

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
  return {rule.indices, fmt::format("indices ({} given)", rule.indices.size())};
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
  Area area;
  for (Eigen::Index v = 0; v < inputs.ligament->V.rows(); ++v)
    if (query.distance(inputs.ligament->V.row(v).transpose()) <= rule.distance_mm)
      area.vertices.push_back(static_cast<int>(v));
  area.rule = fmt::format("proximity: within {} mm of the {}", rule.distance_mm,
                          bone == Bone::femur ? "femur" : "tibia");
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

Area from_landmark(const Rule& rule, const Inputs& inputs, Bone bone)
{
  Eigen::Vector3d centre = rule.point_mm;
  std::string what = "the given point";
  if (!rule.landmark.empty()) {
    const auto found = inputs.landmarks.find(rule.landmark);
    if (found == inputs.landmarks.end()) {
      std::string known;
      for (const auto& [name, point] : inputs.landmarks)
        known += (known.empty() ? "" : ", ") + name;
      fail("{} attachment: no landmark '{}' in the anatomy (known: {})", name_of(bone),
           rule.landmark, known.empty() ? "none" : known);
    }
    centre = found->second;
    what = "landmark " + rule.landmark;
  }
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
  if (!centre.allFinite())
    fail("{} attachment: rule 'landmark' needs `landmark` (a name) or `point_mm`", name_of(bone));
  if (!(rule.radius_mm > 0.0))
    fail("{} attachment: landmark radius must be positive, got {} mm", name_of(bone),
         rule.radius_mm);
  Area area;
  for (Eigen::Index v = 0; v < inputs.ligament->V.rows(); ++v)
    if ((inputs.ligament->V.row(v).transpose() - centre).norm() <= rule.radius_mm)
      area.vertices.push_back(static_cast<int>(v));
  area.rule = fmt::format("landmark: within {} mm of {} ({:.2f}, {:.2f}, {:.2f})", rule.radius_mm,
                          what, centre.x(), centre.y(), centre.z());
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

  auto direct = [&](const std::string& kind, const Rule& rule, Bone bone) -> std::optional<Area> {
    if (kind == "indices")
      return from_indices(rule, inputs, bone);
    if (kind == "array")
      return from_array(rule, inputs, bone);
    if (kind == "proximity")
      return from_proximity(rule, inputs, bone);
    if (kind == "patch")
      return from_patch(rule, inputs, bone);
    if (kind == "landmark")
      return from_landmark(rule, inputs, bone);
    if (kind == "end")
      return std::nullopt;
    fail("{} attachment: unknown rule '{}' (use auto, indices, array, proximity, patch, landmark "
         "or end)",
         name_of(bone), kind);
  };
  const auto near_bone = [&](std::optional<Area>& area, const std::string& kind, const Rule& rule,
                             Bone bone) {
    if (area && kind != "indices" && kind != "array")
      keep_next_to_bone(*area, rule, inputs, bone);
  };

  Attachments result;
  std::optional<Area> femur = direct(femur_kind, femur_rule, Bone::femur);
  std::optional<Area> tibia = direct(tibia_kind, tibia_rule, Bone::tibia);
  near_bone(femur, femur_kind, femur_rule, Bone::femur);
  near_bone(tibia, tibia_kind, tibia_rule, Bone::tibia);
  if (femur)
    finish(*femur, *inputs.ligament, Bone::femur);
  if (tibia)
    finish(*tibia, *inputs.ligament, Bone::tibia);
  // End rules last: "auto" ends look away from the other area when it is known.
  if (!tibia) {
    tibia = from_end(tibia_rule, inputs, Bone::tibia, femur ? &*femur : nullptr);
    near_bone(tibia, tibia_kind, tibia_rule, Bone::tibia);
    finish(*tibia, *inputs.ligament, Bone::tibia);
  }
  if (!femur) {
    femur = from_end(femur_rule, inputs, Bone::femur, &*tibia);
    near_bone(femur, femur_kind, femur_rule, Bone::femur);
    finish(*femur, *inputs.ligament, Bone::femur);
  }

  std::vector<int> shared;
  std::set_intersection(femur->vertices.begin(), femur->vertices.end(), tibia->vertices.begin(),
                        tibia->vertices.end(), std::back_inserter(shared));
  if (!shared.empty()) {
    const Eigen::Vector3d p = inputs.ligament->V.row(shared.front());
    fail("the femoral and tibial attachment areas overlap in {} vertices (first: vertex {} at "
         "({:.2f}, {:.2f}, {:.2f}) mm)",
         shared.size(), shared.front(), p.x(), p.y(), p.z());
  }
  result.femur = std::move(*femur);
  result.tibia = std::move(*tibia);
  return result;
}

} // namespace ligsim::attachments
