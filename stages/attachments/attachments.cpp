#include "stages/attachments/attachments.hpp"

#include "common/error.hpp"
#include "stages/geometry/surface_query.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>

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
  if (rule.end == "min" || rule.end == "max") {
    at_max = rule.end == "max";
    why = rule.end;
  } else if (rule.end != "auto") {
    fail("{} attachment: end must be 'min', 'max' or 'auto', got '{}'", name_of(bone), rule.end);
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
    if (kind == "end")
      return std::nullopt;
    fail("{} attachment: unknown rule '{}' (use auto, indices, array, proximity or end)",
         name_of(bone), kind);
  };

  Attachments result;
  std::optional<Area> femur = direct(femur_kind, femur_rule, Bone::femur);
  std::optional<Area> tibia = direct(tibia_kind, tibia_rule, Bone::tibia);
  if (femur)
    finish(*femur, *inputs.ligament, Bone::femur);
  if (tibia)
    finish(*tibia, *inputs.ligament, Bone::tibia);
  // End rules last: "auto" ends look away from the other area when it is known.
  if (!tibia) {
    tibia = from_end(tibia_rule, inputs, Bone::tibia, femur ? &*femur : nullptr);
    finish(*tibia, *inputs.ligament, Bone::tibia);
  }
  if (!femur) {
    femur = from_end(femur_rule, inputs, Bone::femur, &*tibia);
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
