#include "common/error.hpp"
#include "common/toml_numbers.hpp"
#include "sim/membrane/scene/scene.hpp"

#include <toml++/toml.h>

#include <cmath>
#include <fstream>
#include <initializer_list>
#include <set>
#include <sstream>

namespace ligsim::membrane {
namespace {

constexpr double kDegree = M_PI / 180.0;

/// Reads values of one TOML table, naming the file and table in every error.
class TableReader {
public:
  TableReader(const toml::table* table, std::string where)
      : m_table(table)
      , m_where(std::move(where))
  {
  }

  /// Throws on keys outside `allowed` (typos would otherwise be ignored silently).
  void only(std::initializer_list<const char*> allowed) const
  {
    if (!m_table)
      return;
    const std::set<std::string> names(allowed.begin(), allowed.end());
    for (const auto& [key, value] : *m_table)
      if (!names.count(std::string(key.str())))
        fail("{}: unknown key '{}'", m_where, key.str());
  }

  bool has(const char* key) const { return m_table && m_table->contains(key); }

  double number(const char* key) const
  {
    const auto value = optional_number(key);
    if (!value)
      fail("{}: missing number '{}'", m_where, key);
    return *value;
  }

  double number(const char* key, double fallback) const
  {
    return optional_number(key).value_or(fallback);
  }

  std::optional<double> optional_number(const char* key) const
  {
    if (!has(key))
      return std::nullopt;
    const auto value = toml_number(*m_table->get(key));
    if (!value || !std::isfinite(*value))
      fail("{}: '{}' must be a finite number", m_where, key);
    return value;
  }

  long long integer(const char* key, long long fallback) const
  {
    if (!has(key))
      return fallback;
    const auto value = (*m_table)[key].value_exact<int64_t>();
    if (!value)
      fail("{}: '{}' must be an integer", m_where, key);
    return *value;
  }

  bool boolean(const char* key, bool fallback) const
  {
    if (!has(key))
      return fallback;
    const auto value = (*m_table)[key].value_exact<bool>();
    if (!value)
      fail("{}: '{}' must be true or false", m_where, key);
    return *value;
  }

  std::string text(const char* key, const std::string& fallback) const
  {
    if (!has(key))
      return fallback;
    const auto value = (*m_table)[key].value_exact<std::string>();
    if (!value)
      fail("{}: '{}' must be a string", m_where, key);
    return *value;
  }

  Vec2 point(const char* key, const Vec2& fallback) const
  {
    if (!has(key))
      return fallback;
    return point_from((*m_table)[key].as_array(), key);
  }

  std::vector<Vec2> points(const char* key) const
  {
    const toml::array* list = has(key) ? (*m_table)[key].as_array() : nullptr;
    if (!list)
      fail("{}: missing list of points '{}'", m_where, key);
    std::vector<Vec2> result;
    for (const toml::node& item : *list)
      result.push_back(point_from(item.as_array(), key));
    return result;
  }

  Eigen::Vector4d box(const char* key) const
  {
    const toml::array* list = has(key) ? (*m_table)[key].as_array() : nullptr;
    if (!list || list->size() != 4)
      fail("{}: '{}' must be [x_min, y_min, x_max, y_max]", m_where, key);
    Eigen::Vector4d box;
    for (int i = 0; i < 4; ++i) {
      const auto value = toml_number(*list->get(i));
      if (!value)
        fail("{}: '{}' must hold numbers", m_where, key);
      box[i] = *value;
    }
    if (!(box[0] < box[2]) || !(box[1] < box[3]))
      fail("{}: '{}' needs x_min < x_max and y_min < y_max", m_where, key);
    return box;
  }

  const std::string& where() const { return m_where; }

private:
  Vec2 point_from(const toml::array* pair, const char* key) const
  {
    const auto x = pair && pair->size() == 2 ? toml_number(*pair->get(0)) : std::nullopt;
    const auto y = pair && pair->size() == 2 ? toml_number(*pair->get(1)) : std::nullopt;
    if (!x || !y)
      fail("{}: '{}' must be a point [x, y]", m_where, key);
    return {*x, *y};
  }

  const toml::table* m_table;
  std::string m_where;
};

TableReader section(const toml::table& root, const char* name, const std::string& file,
                    bool required)
{
  const toml::table* table = root[name].as_table();
  if (!table && required)
    fail("{}: missing table [{}]", file, name);
  return {table, fmt::format("{} [{}]", file, name)};
}

double positive(const TableReader& reader, const char* key)
{
  const double value = reader.number(key);
  if (!(value > 0.0))
    fail("{}: '{}' must be positive, got {}", reader.where(), key, value);
  return value;
}

Region read_region(const TableReader& reader)
{
  Region region;
  if (reader.has("box_mm")) {
    region.kind = Region::Kind::box;
    region.box_mm = reader.box("box_mm");
  } else if (reader.has("outside_radius_mm")) {
    region.kind = Region::Kind::outside_circle;
    region.radius_mm = positive(reader, "outside_radius_mm");
    region.centre_mm = reader.point("centre_mm", Vec2::Zero());
  } else {
    fail("{}: a region needs 'box_mm' or 'outside_radius_mm'", reader.where());
  }
  return region;
}

std::vector<double> read_angles(const std::filesystem::path& file, const std::string& where)
{
  std::ifstream in(file);
  if (!in)
    fail("{}: cannot read fiber file {}", where, file.string());
  std::vector<double> angles;
  std::string word;
  while (in >> word) {
    std::istringstream parse(word);
    double degrees = 0.0;
    if (!(parse >> degrees) || !parse.eof() || !std::isfinite(degrees))
      fail("{}: fiber file {}: '{}' (value {}) is not an angle in degrees", where, file.string(),
           word, angles.size() + 1);
    angles.push_back(degrees * kDegree);
  }
  if (angles.empty())
    fail("{}: fiber file {} holds no angle", where, file.string());
  return angles;
}

} // namespace

bool Region::contains(const Vec2& p) const
{
  if (kind == Kind::box)
    return p.x() >= box_mm[0] && p.y() >= box_mm[1] && p.x() <= box_mm[2] && p.y() <= box_mm[3];
  return (p - centre_mm).norm() >= radius_mm;
}

Scene load_scene(const std::filesystem::path& file)
{
  if (!std::filesystem::is_regular_file(file))
    fail("scene file {} does not exist", file.string());
  toml::table root;
  try {
    root = toml::parse_file(file.string());
  } catch (const toml::parse_error& error) {
    fail("{}:{}: {}", file.string(), error.source().begin.line, error.description());
  }
  const std::string name = file.string();
  Scene scene;
  scene.source = file;
  const TableReader top(&root, name);
  top.only({"name", "description", "mesh", "material", "fibers", "tearing", "solver", "run",
            "fixed", "traction", "grasp", "cut"});
  scene.name = top.text("name", file.stem().string());

  const TableReader mesh = section(root, "mesh", name, true);
  mesh.only({"shape", "width_mm", "height_mm", "radius_mm", "element_size_mm", "jitter", "seed"});
  const std::string shape = mesh.text("shape", "");
  if (shape == "rectangle") {
    scene.mesh.shape = MeshSpec::Shape::rectangle;
    scene.mesh.width_mm = positive(mesh, "width_mm");
    scene.mesh.height_mm = positive(mesh, "height_mm");
  } else if (shape == "disc") {
    scene.mesh.shape = MeshSpec::Shape::disc;
    scene.mesh.radius_mm = positive(mesh, "radius_mm");
  } else {
    fail("{}: shape must be \"rectangle\" or \"disc\", got \"{}\"", mesh.where(), shape);
  }
  scene.mesh.element_size_mm = positive(mesh, "element_size_mm");
  scene.mesh.jitter = mesh.number("jitter", 0.15);
  if (scene.mesh.jitter < 0.0 || scene.mesh.jitter > 0.3)
    fail("{}: jitter must be in [0, 0.3], got {}", mesh.where(), scene.mesh.jitter);
  scene.mesh.seed = static_cast<std::uint64_t>(mesh.integer("seed", 1));

  const TableReader material = section(root, "material", name, true);
  material.only({"fiber_modulus_mpa", "transverse_modulus_mpa", "fiber_poisson",
                 "shear_modulus_mpa", "thickness_mm", "density_t_per_mm3"});
  scene.material.fiber_modulus_mpa = material.number("fiber_modulus_mpa");
  scene.material.transverse_modulus_mpa = material.number("transverse_modulus_mpa");
  scene.material.fiber_poisson = material.number("fiber_poisson");
  scene.material.shear_modulus_mpa = material.number("shear_modulus_mpa");
  scene.material.thickness_mm = material.number("thickness_mm");
  scene.material.density_t_per_mm3 = material.number("density_t_per_mm3");
  validate(scene.material, material.where());

  const TableReader fibers = section(root, "fibers", name, true);
  fibers.only({"kind", "angle_deg", "centre_mm", "path"});
  const std::string kind = fibers.text("kind", "");
  if (kind == "uniform") {
    scene.fibers.kind = FiberSpec::Kind::uniform;
    scene.fibers.angle_rad = fibers.number("angle_deg") * kDegree;
  } else if (kind == "concentric") {
    scene.fibers.kind = FiberSpec::Kind::concentric;
    scene.fibers.centre_mm = fibers.point("centre_mm", Vec2::Zero());
  } else if (kind == "per_element") {
    scene.fibers.kind = FiberSpec::Kind::per_element;
    const std::filesystem::path path = fibers.text("path", "");
    if (path.empty())
      fail("{}: kind \"per_element\" needs 'path'", fibers.where());
    scene.fibers.angles_rad = read_angles(file.parent_path() / path, fibers.where());
  } else {
    fail("{}: kind must be \"uniform\", \"concentric\" or \"per_element\", got \"{}\"",
         fibers.where(), kind);
  }

  const TableReader tearing = section(root, "tearing", name, true);
  tearing.only({"fiber_threshold_mpa", "transverse_threshold_mpa", "steepness_alpha",
                "max_turn_deg", "split_faces", "min_angle_deg", "min_area_mm2", "initiation",
                "initiation_clearance_mm", "max_events_per_step"});
  TearSettings& tear = scene.tearing;
  tear.thresholds.fiber_mpa = tearing.number("fiber_threshold_mpa");
  tear.thresholds.transverse_mpa = tearing.number("transverse_threshold_mpa");
  tear.thresholds.steepness = tearing.number("steepness_alpha", 1.0);
  tear.thresholds.max_turn_rad = tearing.number("max_turn_deg", 90.0) * kDegree;
  tear.propagation.split_faces = tearing.boolean("split_faces", true);
  tear.propagation.min_angle_rad = tearing.number("min_angle_deg", 10.0) * kDegree;
  tear.propagation.min_area_mm2 = tearing.number("min_area_mm2", 1e-6);
  tear.initiation = tearing.boolean("initiation", true);
  tear.initiation_clearance_mm = tearing.number("initiation_clearance_mm", 0.0);
  tear.max_events_per_step = static_cast<int>(tearing.integer("max_events_per_step", 2));
  validate(tear, tearing.where().c_str());

  const TableReader solver = section(root, "solver", name, true);
  solver.only({"time_step_s", "mass_damping_per_s", "stiffness_damping_s", "cg_tolerance",
               "cg_max_iterations"});
  scene.solver.time_step_s = solver.number("time_step_s");
  scene.solver.mass_damping_per_s = solver.number("mass_damping_per_s", 0.0);
  scene.solver.stiffness_damping_s = solver.number("stiffness_damping_s", 0.0);
  scene.solver.cg_tolerance = solver.number("cg_tolerance", 1e-6);
  scene.solver.cg_max_iterations = static_cast<int>(solver.integer("cg_max_iterations", 200));
  validate(scene.solver, solver.where().c_str());

  const TableReader run = section(root, "run", name, true);
  run.only({"max_steps", "frame_every", "stop_when_separated", "stop_after_turn_deg", "centre_mm"});
  scene.run.max_steps = static_cast<int>(run.integer("max_steps", 1000));
  scene.run.frame_every = static_cast<int>(run.integer("frame_every", 10));
  if (scene.run.max_steps < 1 || scene.run.frame_every < 1)
    fail("{}: max_steps and frame_every must be at least 1", run.where());
  scene.run.stop_when_separated = run.boolean("stop_when_separated", true);
  scene.run.stop_after_turn_rad = run.number("stop_after_turn_deg", 0.0) * kDegree;
  if (run.has("centre_mm"))
    scene.run.centre_mm = run.point("centre_mm", Vec2::Zero());

  const auto array_of_tables = [&](const char* key) {
    std::vector<TableReader> readers;
    if (!root.contains(key))
      return readers;
    const toml::array* list = root[key].as_array();
    if (!list || !list->is_array_of_tables())
      fail("{}: '{}' must be written [[{}]]", name, key, key);
    for (std::size_t i = 0; i < list->size(); ++i)
      readers.emplace_back((*list)[i].as_table(), fmt::format("{} [[{}]] #{}", name, key, i + 1));
    return readers;
  };
  for (const TableReader& fixed : array_of_tables("fixed")) {
    fixed.only({"box_mm", "outside_radius_mm", "centre_mm", "velocity_mm_per_s"});
    scene.fixed.push_back({read_region(fixed), fixed.point("velocity_mm_per_s", Vec2::Zero())});
  }
  for (const TableReader& traction : array_of_tables("traction")) {
    traction.only({"box_mm", "outside_radius_mm", "centre_mm", "direction", "rate_n_per_mm_per_s",
                   "max_n_per_mm"});
    TractionSpec spec;
    spec.region = read_region(traction);
    spec.direction = traction.point("direction", Vec2::Zero());
    if (!(spec.direction.norm() > 0.0))
      fail("{}: 'direction' must be a non-zero vector", traction.where());
    spec.direction.normalize();
    spec.rate_n_per_mm_per_s = positive(traction, "rate_n_per_mm_per_s");
    spec.max_n_per_mm = positive(traction, "max_n_per_mm");
    scene.tractions.push_back(spec);
  }
  if (scene.tractions.size() > 255)
    fail("{}: at most 255 [[traction]] tables", name);
  if (root.contains("grasp")) {
    const TableReader grasp = section(root, "grasp", name, true);
    grasp.only({"centre_mm", "radius_mm", "force_rate_n_per_s", "max_force_n", "inward_deg"});
    GraspSpec spec;
    spec.centre_mm = grasp.point("centre_mm", Vec2::Zero());
    spec.radius_mm = positive(grasp, "radius_mm");
    spec.force_rate_n_per_s = positive(grasp, "force_rate_n_per_s");
    spec.max_force_n = positive(grasp, "max_force_n");
    spec.inward_rad = grasp.number("inward_deg", 0.0) * kDegree;
    scene.grasp = spec;
  }
  for (const TableReader& cut : array_of_tables("cut")) {
    cut.only({"points_mm", "tear_from"});
    CutSpec spec;
    spec.points_mm = cut.points("points_mm");
    if (spec.points_mm.size() < 2)
      fail("{}: 'points_mm' needs at least two points", cut.where());
    const std::string from = cut.text("tear_from", "both");
    if (from != "both" && from != "start" && from != "end" && from != "none")
      fail("{}: tear_from must be \"both\", \"start\", \"end\" or \"none\", got \"{}\"",
           cut.where(), from);
    spec.tear_from_start = from == "both" || from == "start";
    spec.tear_from_end = from == "both" || from == "end";
    scene.cuts.push_back(spec);
  }
  return scene;
}

} // namespace ligsim::membrane
