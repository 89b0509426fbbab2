#include "sim/flexion/knee_model.hpp"

#include "common/error.hpp"
#include "common/vtk_files.hpp"
#include "sim/scene/scene.hpp"
#include "sim/scene/vtu_mesh.hpp"
#include "stages/io/vtk_convert.hpp"

#include <vtkPolyData.h>

#include <map>

namespace ligsim::sim {

namespace fs = std::filesystem;

namespace {

/// Nodes whose flag in `array` of model.vtu is set.
std::vector<int> flagged_nodes(const VtuMesh& vtu, const fs::path& file, const std::string& array,
                               const std::string& bone)
{
  const auto found = vtu.point_data.find(array);
  if (found == vtu.point_data.end())
    fail("{}: no point data '{}': the model has no {} attachment set (was it built with "
         "`ligsim build`?)",
         file.string(), array, bone);
  std::vector<int> nodes;
  for (Eigen::Index n = 0; n < found->second.rows(); ++n)
    if (found->second(n, 0) != 0.0)
      nodes.push_back(static_cast<int>(n));
  if (nodes.empty())
    fail("{}: the {} attachment set '{}' is empty: no node is attached to the {}", file.string(),
         bone, array, bone);
  return nodes;
}

/// A bone's surface file, checked: triangles only (the pipeline writes no other polygon), some
/// of them, every point finite. Throws InputError naming the file.
BoneSurface bone_surface(const fs::path& dir, const std::string& name, const std::string& bone)
{
  const fs::path file = dir / name;
  if (!fs::exists(file))
    fail("{}: the model has no {} surface: give the {} to `ligsim build` (--{} or [input] {})",
         file.string(), bone, bone, bone, bone);
  TriangleSurface surface;
  try {
    surface = io::from_polydata(read_vtp(file));
  } catch (const InputError& error) {
    fail("{}: {}", file.string(), error.what());
  }
  if (surface.V.rows() == 0 || surface.F.rows() == 0)
    fail("{}: the surface has no points or no triangles", file.string());
  for (Eigen::Index p = 0; p < surface.V.rows(); ++p)
    if (!surface.V.row(p).allFinite())
      fail("{}: point {} is not finite", file.string(), p);
  return std::make_shared<const TriangleSurface>(std::move(surface));
}

} // namespace

Eigen::Vector3d proximal_direction(const KneeModel& model)
{
  const Eigen::RowVector3d up = model.femur->V.colwise().mean() - model.tibia->V.colwise().mean();
  return up.transpose().normalized();
}

const TriangleSurface* bone_of(const KneeModel& model, const std::string& name)
{
  if (name == "femur")
    return model.femur.get();
  if (name == "tibia")
    return model.tibia.get();
  if (name == "fibula")
    return model.fibula.get();
  return nullptr;
}

const std::vector<int>& nodes_bound_to(const KneeModel& model, const std::string& bone)
{
  static const std::vector<int> none;
  if (bone == "femur")
    return model.femur_nodes;
  return bone == model.distal_bone ? model.tibia_nodes : none;
}

std::vector<std::string> contact_bones(const KneeModel& model,
                                       const std::vector<std::string>& chosen)
{
  if (!chosen.empty())
    return chosen;
  std::vector<std::string> bones;
  for (const char* name : {"femur", "tibia", "fibula"})
    if (bone_of(model, name))
      bones.push_back(name);
  return bones;
}

std::string ligament_names(const std::vector<LigamentModel>& ligaments)
{
  std::string names;
  for (const LigamentModel& ligament : ligaments)
    names += (names.empty() ? "" : ", ") + ligament.name;
  return names;
}

std::optional<std::pair<fs::path, KneeLigament>> knee_of_ligament_folder(const fs::path& dir)
{
  const fs::path folder = fs::absolute(dir).lexically_normal();
  const fs::path knee =
      folder.has_filename() ? folder.parent_path() : folder.parent_path().parent_path();
  const std::string name = (folder.has_filename() ? folder : folder.parent_path()).filename();
  if (const auto parent = read_knee_manifest(knee))
    for (const KneeLigament& entry : parent->ligaments)
      if (entry.folder == name)
        return std::make_pair(knee, entry);
  return std::nullopt;
}

std::vector<LigamentModel> load_knee(const fs::path& dir, const std::string& single_name)
{
  const std::optional<KneeManifest> manifest = read_knee_manifest(dir);
  if (!manifest) {
    // One ligament's folder of a knee: that ligament of the knee, with the knee's bones.
    if (const auto knee = knee_of_ligament_folder(dir)) {
      std::vector<LigamentModel> all = load_knee(knee->first, single_name);
      for (LigamentModel& ligament : all)
        if (ligament.name == knee->second.name)
          return {std::move(ligament)};
    }
    return {{single_name, load_knee_model(dir), dir, std::nullopt, read_built_material(dir)}};
  }
  std::map<std::string, BoneSurface> bones;
  for (const auto& [name, file] : manifest->bones)
    bones[name] = bone_surface(dir, file, name);
  const KneeAnatomy anatomy = read_knee_anatomy(dir);
  std::vector<LigamentModel> ligaments;
  for (const KneeLigament& entry : manifest->ligaments) {
    LigamentModel ligament{entry.name, load_knee_model(dir / entry.folder), dir / entry.folder,
                           entry, std::nullopt};
    KneeModel& model = ligament.model;
    if (!bones.count("femur"))
      fail("{}: this knee has no femur (its label map names none), and a flexion turns the "
           "femur: rebuild it with the femur's label (the knee config's [input] femur_label; a "
           "femoral cartilage label can stand in, as data/vhf-right-knee/mcl_labels.toml has it)",
           dir.string());
    model.femur = bones.at("femur");
    model.tibia = bones.at("tibia");
    model.fibula = bones.count("fibula") ? bones.at("fibula") : nullptr;
    model.distal_bone = entry.distal_bone;
    model.anatomy = anatomy;
    ligaments.push_back(std::move(ligament));
  }
  return ligaments;
}

LigamentModel load_ligament(const fs::path& dir, const std::string& single_name,
                            const std::string& job)
{
  std::vector<LigamentModel> all = load_knee(dir, single_name);
  if (all.size() > 1)
    fail("{}: {} is a knee of {} ligaments ({}): give one ligament's folder (--model {})", job,
         dir.string(), all.size(), ligament_names(all), all.front().folder.string());
  return std::move(all.front());
}

std::optional<BuiltMaterial> read_built_material(const fs::path& dir)
{
  const fs::path file = dir / "scene.toml";
  if (!fs::exists(file))
    return std::nullopt;
  const Scene scene = load_scene(file);
  if (scene.fibers.rows() == 0)
    return std::nullopt;
  return BuiltMaterial{scene.material, scene.fibers.row(0).norm() - 1.0};
}

KneeModel with_quadratic_tets(const KneeModel& model)
{
  if (model.tet10.rows() > 0)
    return model;
  KneeModel quadratic = model;
  const QuadraticTetMesh promoted = promote_to_quadratic(model.mesh);
  quadratic.mesh.V = promoted.V;
  quadratic.tet10 = promoted.T;
  auto extended = [&](const std::vector<int>& nodes) {
    std::vector<bool> bound(static_cast<std::size_t>(promoted.V.rows()), false);
    for (int n : nodes)
      bound[static_cast<std::size_t>(n)] = true;
    flag_mid_edge_nodes(promoted.T, bound);
    std::vector<int> result = nodes;
    for (auto n = static_cast<std::size_t>(model.mesh.V.rows()); n < bound.size(); ++n)
      if (bound[n])
        result.push_back(static_cast<int>(n));
    return result;
  };
  quadratic.femur_nodes = extended(model.femur_nodes);
  quadratic.tibia_nodes = extended(model.tibia_nodes);
  return quadratic;
}

KneeModel with_linear_tets(const KneeModel& model)
{
  if (model.tet10.rows() == 0)
    return model;
  KneeModel linear = model;
  // The corners, numbered in node order: a build's model (corners first) keeps their indices.
  std::vector<int> index(static_cast<std::size_t>(model.mesh.V.rows()), -1);
  for (Eigen::Index e = 0; e < model.mesh.T.rows(); ++e)
    for (int k = 0; k < 4; ++k)
      index[static_cast<std::size_t>(model.mesh.T(e, k))] = 0;
  int corners = 0;
  for (int& i : index)
    if (i >= 0)
      i = corners++;
  linear.mesh.V.resize(corners, 3);
  for (std::size_t n = 0; n < index.size(); ++n)
    if (index[n] >= 0)
      linear.mesh.V.row(index[n]) = model.mesh.V.row(static_cast<Eigen::Index>(n));
  for (Eigen::Index e = 0; e < model.mesh.T.rows(); ++e)
    for (int k = 0; k < 4; ++k)
      linear.mesh.T(e, k) = index[static_cast<std::size_t>(model.mesh.T(e, k))];
  for (std::vector<int>* nodes : {&linear.femur_nodes, &linear.tibia_nodes}) {
    std::vector<int> kept;
    for (int n : *nodes)
      if (index[static_cast<std::size_t>(n)] >= 0)
        kept.push_back(index[static_cast<std::size_t>(n)]);
    *nodes = std::move(kept);
  }
  linear.tet10.resize(0, 10);
  linear.fiber_directions_at_points.resize(0, 3);
  return linear;
}

HyperelasticBody ligament_body(const KneeModel& model, const MaterialParameters& material,
                               double in_situ_strain)
{
  if (model.tet10.rows() == 0)
    return HyperelasticBody(model.mesh, material, model.fiber_directions * (1.0 + in_situ_strain));
  const Eigen::MatrixX3d& directions = model.fiber_directions_at_points.rows() > 0
                                           ? model.fiber_directions_at_points
                                           : model.fiber_directions;
  return HyperelasticBody(QuadraticTetMesh{model.mesh.V, model.tet10}, material,
                          directions * (1.0 + in_situ_strain),
                          tet_quadrature(kQuadraticTetRuleDegree));
}

KneeModel load_knee_model(const fs::path& dir)
{
  if (!fs::is_directory(dir))
    fail("model folder {} does not exist: build the model first (`ligsim build --out {}`)",
         dir.string(), dir.string());
  const fs::path file = dir / "model.vtu";
  if (!fs::exists(file))
    fail("{}: no model in this folder: run `ligsim build` (or its `model` stage) on it first",
         file.string());
  VtuMesh vtu = read_vtu_mesh(file);
  KneeModel model;
  model.mesh = std::move(vtu.mesh);
  model.tet10 = std::move(vtu.tet10);

  const auto fibers = vtu.cell_data.find("fiber");
  if (fibers == vtu.cell_data.end() || fibers->second.cols() != 3)
    fail("{}: no 3-component cell data 'fiber' (the per-tet fiber directions)", file.string());
  model.fiber_directions.resize(fibers->second.rows(), 3);
  for (Eigen::Index e = 0; e < fibers->second.rows(); ++e) {
    const Eigen::Vector3d a = fibers->second.row(e).transpose();
    if (!a.allFinite() || a.norm() < 1e-9)
      fail("{}: the fiber of tet {} is zero or not finite", file.string(), e);
    model.fiber_directions.row(e) = a.normalized().transpose();
  }
  if (const auto at_points = vtu.cell_data.find(kFibersAtPoints);
      model.tet10.rows() > 0 && at_points != vtu.cell_data.end()) {
    const int points = static_cast<int>(tet_quadrature(kQuadraticTetRuleDegree).points.size());
    if (at_points->second.cols() != 3 * points)
      fail("{}: cell data '{}' has {} components, not 3 for each of the {} points of a tet",
           file.string(), kFibersAtPoints, at_points->second.cols(), points);
    model.fiber_directions_at_points.resize(at_points->second.rows() * points, 3);
    for (Eigen::Index e = 0; e < at_points->second.rows(); ++e)
      for (int q = 0; q < points; ++q) {
        const Eigen::Vector3d a = at_points->second.block<1, 3>(e, 3 * q).transpose();
        if (!a.allFinite() || a.norm() < 1e-9)
          fail("{}: the fiber of tet {} at its point {} is zero or not finite", file.string(), e,
               q);
        model.fiber_directions_at_points.row(e * points + q) = a.normalized().transpose();
      }
  }

  model.femur_nodes = flagged_nodes(vtu, file, "femur_attached", "femur");
  model.tibia_nodes = flagged_nodes(vtu, file, "tibia_attached", "tibia");
  std::vector<bool> on_femur(static_cast<std::size_t>(model.mesh.V.rows()), false);
  for (int n : model.femur_nodes)
    on_femur[static_cast<std::size_t>(n)] = true;
  for (int n : model.tibia_nodes)
    if (on_femur[static_cast<std::size_t>(n)])
      fail("{}: node {} is attached to both the femur and the tibia", file.string(), n);

  model.femur = bone_surface(dir, "femur.vtp", "femur");
  model.tibia = bone_surface(dir, "tibia.vtp", "tibia");
  model.anatomy = read_knee_anatomy(dir);
  if (fs::exists(dir / "centerline.vtp"))
    model.centerline = io::points_of(read_vtp(dir / "centerline.vtp"));
  return model;
}

} // namespace ligsim::sim
