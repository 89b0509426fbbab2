#include "common/config_section.hpp"
#include "common/error.hpp"
#include "common/toml_overrides.hpp"
#include "common/toml_table.hpp"
#include "sim/mesh/node_selection.hpp"
#include "sim/mesh/structured_mesh.hpp"
#include "sim/scene/contact_table.hpp"
#include "sim/scene/scene.hpp"
#include "sim/scene/scene_fields.hpp"
#include "sim/scene/vtu_mesh.hpp"

#include <fmt/format.h>

#include <cmath>

namespace ligsim::sim {

namespace fs = std::filesystem;

namespace {

constexpr double pi = 3.14159265358979323846;

struct MeshData {
  TetMesh mesh;
  QuadraticTetrahedra tet10;
  std::string source;
  std::map<std::string, Eigen::MatrixXd> point_data;
  std::map<std::string, Eigen::MatrixXd> cell_data;
};

MeshData read_mesh(TomlTable& table, const fs::path& base)
{
  MeshData data;
  if (table.has("file") == table.has("generator"))
    table.fail_at("file", "give exactly one of 'file' (a .vtu) and 'generator'");
  if (table.has("file")) {
    const fs::path file = base / table.required_text("file");
    VtuMesh vtu = read_vtu_mesh(file);
    data.mesh = std::move(vtu.mesh);
    data.tet10 = std::move(vtu.tet10);
    data.point_data = std::move(vtu.point_data);
    data.cell_data = std::move(vtu.cell_data);
    data.source = "file " + file.string();
  } else {
    const std::string generator = table.required_text("generator");
    if (generator == "cube") {
      const int cells = table.integer("cells", 8);
      const double edge = table.number("edge_mm", 1.0);
      data.mesh = structured_cube_mesh(cells, edge);
      data.source = fmt::format("cube, {} cells per edge, edge {} mm", cells, edge);
    } else if (generator == "box" || generator == "bent_bar") {
      const Eigen::Vector3i cells = table.integer_vector3("cells");
      const Eigen::Vector3d size = table.required_vector3("size_mm");
      const double bend = generator == "bent_bar" ? table.required_number("bend_deg") : 0.0;
      data.mesh = bent_bar_mesh(cells, size, bend);
      data.source =
          fmt::format("{}, {} x {} x {} cells, {} x {} x {} mm, bend {} deg", generator, cells.x(),
                      cells.y(), cells.z(), size.x(), size.y(), size.z(), bend);
    } else {
      table.fail_at("generator",
                    "expected \"cube\", \"box\" or \"bent_bar\", got \"" + generator + "\"");
    }
  }
  table.reject_unknown_keys();
  return data;
}

/// Reads the settings of `visit_fields` from `table` over `settings`; the caller then reads its
/// own keys and rejects unknown ones.
template <class P, class VisitFields>
void read_listed(TomlTable& table, P& settings, VisitFields visit_fields)
{
  ConfigSection section(table);
  visit_fields(settings, FieldReader{section});
}

MaterialParameters read_material(TomlTable& table)
{
  MaterialParameters material;
  read_listed(table, material, [](auto& m, auto&& v) { visit_ground_substance(m, v); });
  table.reject_unknown_keys();
  return material;
}

/// Reads [fibers] into the material's fiber law and returns the fiber field.
FiberField read_fibers(TomlTable& table, const MeshData& mesh, MaterialParameters& material)
{
  FiberParameters fiber;
  read_listed(table, fiber, [](auto& f, auto&& v) { visit_fiber_law(f, v); });
  material.fiber = fiber;

  FiberField field;
  if (table.has("direction") == table.has("cell_data"))
    table.fail_at("direction", "give exactly one of 'direction' and 'cell_data'");
  if (table.has("direction")) {
    const Eigen::Vector3d direction = table.required_vector3("direction");
    if (direction.norm() < 1e-12)
      table.fail_at("direction", "the fiber direction has zero length");
    field = direction.normalized().transpose();
  } else {
    const std::string name = table.required_text("cell_data");
    const auto found = mesh.cell_data.find(name);
    if (found == mesh.cell_data.end())
      table.fail_at("cell_data", "the mesh has no cell data array '" + name + "'");
    if (found->second.cols() != 3)
      table.fail_at("cell_data", "the array '" + name + "' must have 3 components");
    field = found->second; // used as is: its length carries the in-situ strain (sec. 2.7)
  }
  const double in_situ = table.number("in_situ_strain", 0.0);
  if (in_situ <= -1.0)
    table.fail_at("in_situ_strain", "must be above -1");
  field *= 1.0 + in_situ;
  table.reject_unknown_keys();
  return field;
}

int parse_axis(TomlTable& table, const std::string& key)
{
  const std::string axis = table.required_text(key);
  if (axis == "x")
    return 0;
  if (axis == "y")
    return 1;
  if (axis == "z")
    return 2;
  table.fail_at(key, "expected \"x\", \"y\" or \"z\", got \"" + axis + "\"");
}

std::vector<int> read_node_set(TomlTable& table, const MeshData& mesh)
{
  const Points& V = mesh.mesh.V;
  const double size = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  int ways = 0;
  std::vector<int> nodes;
  if (auto plane = table.table("plane")) {
    ++ways;
    const int axis = parse_axis(*plane, "axis");
    const double at = plane->required_number("at_mm");
    const double tolerance = plane->number("tolerance_mm", 1e-6 * size);
    plane->reject_unknown_keys();
    nodes = nodes_on_plane(V, axis, at, tolerance);
  }
  if (auto box = table.table("box")) {
    ++ways;
    const Eigen::Vector3d low = box->required_vector3("min_mm");
    const Eigen::Vector3d high = box->required_vector3("max_mm");
    box->reject_unknown_keys();
    nodes = nodes_in_box(V, low, high);
  }
  if (table.has("point_data")) {
    ++ways;
    const std::string name = table.required_text("point_data");
    const auto found = mesh.point_data.find(name);
    if (found == mesh.point_data.end())
      table.fail_at("point_data", "the mesh has no point data array '" + name + "'");
    for (Eigen::Index n = 0; n < found->second.rows(); ++n)
      if (found->second.row(n).cwiseAbs().maxCoeff() > 0.0)
        nodes.push_back(static_cast<int>(n));
  }
  if (table.has("nodes")) {
    ++ways;
    nodes = table.integers("nodes");
    for (int node : nodes)
      if (node < 0 || node >= V.rows())
        table.fail_at("nodes", fmt::format("node {} is out of range (the mesh has {} nodes)", node,
                                           V.rows()));
  }
  if (ways != 1)
    table.fail_at("plane", "give exactly one of 'plane', 'box', 'point_data' and 'nodes'");
  table.reject_unknown_keys();
  if (nodes.empty())
    fail("{}: the selection matches no node", table.where());
  return nodes;
}

const std::vector<int>& set_named(TomlTable& table, const Scene& scene)
{
  const std::string name = table.required_text("set");
  const auto found = scene.node_sets.find(name);
  if (found == scene.node_sets.end())
    table.fail_at("set", "no node set named '" + name + "' in [node_sets]");
  return found->second;
}

std::array<bool, 3> read_components(TomlTable& table)
{
  const std::string text = table.text("components", "xyz");
  std::array<bool, 3> components = {false, false, false};
  for (char c : text) {
    if (c < 'x' || c > 'z')
      table.fail_at("components", "expected letters among x, y, z, got \"" + text + "\"");
    components[static_cast<std::size_t>(c - 'x')] = true;
  }
  if (text.empty())
    table.fail_at("components", "empty");
  return components;
}

void read_conditions(TomlTable& root, Scene& scene)
{
  for (TomlTable& table : root.tables("fix")) {
    ConstraintSet set;
    set.name = table.text("set", "");
    set.nodes = set_named(table, scene);
    set.components = read_components(table);
    table.reject_unknown_keys();
    scene.conditions.constraints.push_back(set);
  }
  for (TomlTable& table : root.tables("displace")) {
    ConstraintSet set;
    set.name = table.text("set", "");
    set.nodes = set_named(table, scene);
    auto displacement = table.table("displacement_mm");
    if (!displacement)
      table.fail_at("displacement_mm", "missing (a table such as { z = 0.1 })");
    set.components = {false, false, false};
    for (int a = 0; a < 3; ++a) {
      const std::string axis(1, static_cast<char>('x' + a));
      if (displacement->has(axis)) {
        set.components[static_cast<std::size_t>(a)] = true;
        set.displacement_mm(a) = displacement->required_number(axis);
      }
    }
    displacement->reject_unknown_keys();
    table.reject_unknown_keys();
    scene.conditions.constraints.push_back(set);
  }
  for (TomlTable& table : root.tables("rigid")) {
    ConstraintSet set;
    set.name = table.text("set", "");
    set.nodes = set_named(table, scene);
    RigidMotion motion;
    const Eigen::Vector3d axis = table.vector3("axis", Eigen::Vector3d::UnitX());
    if (axis.norm() < 1e-12)
      table.fail_at("axis", "the rotation axis has zero length");
    motion.axis = axis.normalized();
    motion.point_mm = table.vector3("point_mm", Eigen::Vector3d::Zero());
    motion.angle_rad = table.number("angle_deg", 0.0) * pi / 180.0;
    motion.translation_mm = table.vector3("translation_mm", Eigen::Vector3d::Zero());
    table.reject_unknown_keys();
    set.rigid = motion;
    scene.conditions.constraints.push_back(set);
  }
  for (TomlTable& table : root.tables("force")) {
    NodalLoad load;
    load.name = table.text("set", "");
    load.nodes = set_named(table, scene);
    if (table.has("per_node_n") == table.has("total_n"))
      table.fail_at("per_node_n", "give exactly one of 'per_node_n' and 'total_n'");
    if (table.has("per_node_n"))
      load.force_per_node_n = table.required_vector3("per_node_n");
    else
      load.force_per_node_n =
          table.required_vector3("total_n") / static_cast<double>(load.nodes.size());
    table.reject_unknown_keys();
    scene.conditions.loads.push_back(load);
  }
}

void read_solver(TomlTable& table, Scene& scene)
{
  read_listed(table, scene, [](auto& sc, auto&& v) { visit_scene_solver(sc, v); });
  NewtonSettings& newton = scene.newton;
  if (!table.has("linear_solver") && scene.kind == SceneKind::dynamic)
    newton.linear_solver = LinearSolverKind::pcg;
  scene.dynamics.linear_solver = newton.linear_solver;
  scene.dynamics.pcg = newton.pcg;
  scene.dynamics.projection = newton.projection;
  table.reject_unknown_keys();
  if (newton.load_steps < 1 || newton.max_iterations < 1 || newton.max_cutbacks < 0 ||
      newton.max_substeps < 1)
    fail("{}: load_steps, max_iterations and max_substeps must be at least 1, max_cutbacks not "
         "negative",
         table.where());
  if (!(newton.residual_tolerance > 0.0) || !(newton.pcg.tolerance > 0.0) ||
      newton.energy_tolerance < 0.0)
    fail("{}: tolerances must be positive", table.where());
}

void read_dynamics(TomlTable& table, DynamicsSettings& dynamics)
{
  read_listed(table, dynamics, [](auto& d, auto&& v) { visit_scene_dynamics(d, v); });
  table.reject_unknown_keys();
}

/// [contact] with its [[contact.bone]] tables; a bone follows a [[rigid]] set or stays fixed.
void read_contact(TomlTable& table, const fs::path& base, Scene& scene)
{
  read_contact_table(table, scene.contact);
  scene.contact.enabled = scene.contact.enabled.value_or(true); // a scene's [contact] has bones
  for (TomlTable& bone_table : table.tables("bone")) {
    SceneBone bone;
    bone.name = bone_table.required_text("name");
    bone.surface = base / bone_table.required_text("surface");
    bone.follows = bone_table.text("follows", "");
    bone_table.reject_unknown_keys();
    if (!bone.follows.empty()) {
      bool found = false;
      for (const ConstraintSet& set : scene.conditions.constraints)
        found = found || (set.name == bone.follows && set.rigid);
      if (!found)
        bone_table.fail_at("follows",
                           "no [[rigid]] constraint on a set named '" + bone.follows + "'");
    }
    scene.bones.push_back(bone);
  }
  table.reject_unknown_keys();
  if (scene.bones.empty())
    table.fail_at("bone", "[contact] needs at least one [[contact.bone]]");
  validate(scene.contact);
}

/// The scene of a parsed file (`document`).
Scene read_document(const toml::table& document, const fs::path& base, const std::string& name)
{
  TomlTable root(document, name);
  Scene scene;
  root.text("title", "");

  auto mesh_table = root.table("mesh");
  if (!mesh_table)
    fail("{}: missing [mesh]", name);
  const MeshData mesh = read_mesh(*mesh_table, base);
  scene.mesh = mesh.mesh;
  scene.tet10 = mesh.tet10;
  scene.mesh_source = mesh.source;

  if (auto material = root.table("material"))
    scene.material = read_material(*material);
  if (auto fibers = root.table("fibers"))
    scene.fibers = read_fibers(*fibers, mesh, scene.material);
  validate(scene.material);

  if (auto sets = root.table("node_sets"))
    for (const std::string& key : sets->keys()) {
      auto set = sets->table(key);
      if (!set)
        sets->fail_at(key, "expected a table");
      scene.node_sets[key] = read_node_set(*set, mesh);
    }
  read_conditions(root, scene);

  if (auto solver = root.table("solver"))
    read_solver(*solver, scene);
  else
    scene.dynamics.linear_solver = LinearSolverKind::direct;
  if (auto dynamics = root.table("dynamics")) {
    if (scene.kind != SceneKind::dynamic)
      fail("{}: [dynamics] is given but [solver] kind is not \"dynamic\"", name);
    read_dynamics(*dynamics, scene.dynamics);
  }
  if (auto output = root.table("output")) {
    read_listed(*output, scene.output, [](auto& o, auto&& v) { visit_scene_output(o, v); });
    output->reject_unknown_keys();
    if (scene.output.every < 1)
      fail("{} output: every must be at least 1", name);
  }
  if (auto contact = root.table("contact"))
    read_contact(*contact, base, scene);
  root.reject_unknown_keys();
  if (scene.conditions.constraints.empty())
    fail("{}: no [[fix]], [[displace]] or [[rigid]] constraint: the body could move freely", name);
  return scene;
}

} // namespace

Scene parse_scene(const std::string& text, const fs::path& base, const std::string& name)
{
  return read_document(parse_toml(text, name), base, name);
}

Scene load_scene(const fs::path& file, const std::vector<std::string>& overrides)
{
  toml::table document = parse_toml(read_text_file(file, "scene file"), file.string());
  apply_overrides(document, overrides);
  Scene scene = read_document(document, file.parent_path(), file.string());
  scene.file = file;
  return scene;
}

} // namespace ligsim::sim
