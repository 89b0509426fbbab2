#include "common/config_section.hpp"
#include "common/error.hpp"
#include "common/toml_overrides.hpp"
#include "common/toml_table.hpp"
#include "sim/membrane/scene/scene.hpp"
#include "sim/membrane/scene/scene_fields.hpp"

#include <toml++/toml.h>

#include <cmath>
#include <fstream>
#include <sstream>

namespace ligsim::membrane {
namespace {

constexpr double kDegree = M_PI / 180.0;

/// A point [x, y] (2 numbers).
Vec2 point(TomlTable& table, const char* key, const Vec2& fallback)
{
  if (!table.has(key))
    return fallback;
  const std::vector<double> xy = table.numbers(key);
  if (xy.size() != 2)
    table.fail_at(key, "expected a point [x, y]");
  return {xy[0], xy[1]};
}

std::vector<Vec2> points(TomlTable& table, const char* key)
{
  std::vector<Vec2> result;
  for (const std::vector<double>& xy : table.number_lists(key)) {
    if (xy.size() != 2)
      table.fail_at(key, "expected a list of points [x, y]");
    result.emplace_back(xy[0], xy[1]);
  }
  return result;
}

/// [x_min, y_min, x_max, y_max].
Eigen::Vector4d box(TomlTable& table, const char* key)
{
  const std::vector<double> values = table.numbers(key);
  if (values.size() != 4)
    table.fail_at(key, "expected [x_min, y_min, x_max, y_max]");
  const Eigen::Vector4d result(values[0], values[1], values[2], values[3]);
  if (!(result[0] < result[2]) || !(result[1] < result[3]))
    table.fail_at(key, "needs x_min < x_max and y_min < y_max");
  return result;
}

double positive(TomlTable& table, const char* key)
{
  const double value = table.required_number(key);
  if (!(value > 0.0))
    table.fail_at(key, fmt::format("must be positive, got {}", value));
  return value;
}

Region read_region(TomlTable& table)
{
  Region region;
  if (table.has("box_mm")) {
    region.kind = Region::Kind::box;
    region.box_mm = box(table, "box_mm");
  } else if (table.has("outside_radius_mm")) {
    region.kind = Region::Kind::outside_circle;
    region.radius_mm = positive(table, "outside_radius_mm");
    region.centre_mm = point(table, "centre_mm", Vec2::Zero());
  } else {
    fail("{}: a region needs 'box_mm' or 'outside_radius_mm'", table.where());
  }
  return region;
}

/// Reads a settings table of `visit_fields` over `settings`, after refusing keys that neither the
/// list nor `by_hand` names (so that a mistyped required key is named as the typo it is).
template <class P, class VisitFields>
void read_settings(TomlTable& table, P& settings, VisitFields visit_fields,
                   std::vector<std::string_view> by_hand = {})
{
  visit_fields(settings, FieldNames{by_hand});
  table.only(by_hand);
  ConfigSection section(table);
  visit_fields(settings, FieldReader{section});
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

Scene load_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides)
{
  if (!std::filesystem::is_regular_file(file))
    fail("scene file {} does not exist", file.string());
  toml::table document = parse_toml(read_text_file(file, "scene file"), file.string());
  apply_overrides(document, overrides);
  const std::string name = file.string();
  Scene scene;
  scene.source = file;
  TomlTable top(document, name);
  top.only({"name", "description", "mesh", "material", "fibers", "tearing", "solver", "run",
            "fixed", "traction", "grasp", "cut"});
  scene.name = top.text("name", file.stem().string());

  TomlTable mesh = top.required_table("mesh");
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

  TomlTable material = top.required_table("material");
  read_settings(material, scene.material, [](auto& m, auto&& v) { visit_membrane_material(m, v); });
  validate(scene.material, material.where());

  TomlTable fibers = top.required_table("fibers");
  fibers.only({"kind", "angle_deg", "centre_mm", "path"});
  const std::string kind = fibers.text("kind", "");
  if (kind == "uniform") {
    scene.fibers.kind = FiberSpec::Kind::uniform;
    scene.fibers.angle_rad = fibers.required_number("angle_deg") * kDegree;
  } else if (kind == "concentric") {
    scene.fibers.kind = FiberSpec::Kind::concentric;
    scene.fibers.centre_mm = point(fibers, "centre_mm", Vec2::Zero());
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

  TomlTable tearing = top.required_table("tearing");
  read_settings(tearing, scene.tearing, [](auto& t, auto&& v) { visit_tearing(t, v); });
  validate(scene.tearing, tearing.where().c_str());

  TomlTable solver = top.required_table("solver");
  read_settings(solver, scene.solver, [](auto& s, auto&& v) { visit_membrane_solver(s, v); });
  validate(scene.solver, solver.where().c_str());

  TomlTable run = top.required_table("run");
  read_settings(run, scene.run, [](auto& r, auto&& v) { visit_run(r, v); }, {"centre_mm"});
  if (scene.run.max_steps < 1 || scene.run.frame_every < 1)
    fail("{}: max_steps and frame_every must be at least 1", run.where());
  if (run.has("centre_mm"))
    scene.run.centre_mm = point(run, "centre_mm", Vec2::Zero());

  for (TomlTable& fixed : top.tables("fixed")) {
    fixed.only({"box_mm", "outside_radius_mm", "centre_mm", "velocity_mm_per_s"});
    scene.fixed.push_back({read_region(fixed), point(fixed, "velocity_mm_per_s", Vec2::Zero())});
  }
  for (TomlTable& traction : top.tables("traction")) {
    traction.only({"box_mm", "outside_radius_mm", "centre_mm", "direction", "rate_n_per_mm_per_s",
                   "max_n_per_mm"});
    TractionSpec spec;
    spec.region = read_region(traction);
    spec.direction = point(traction, "direction", Vec2::Zero());
    if (!(spec.direction.norm() > 0.0))
      fail("{}: 'direction' must be a non-zero vector", traction.where());
    spec.direction.normalize();
    spec.rate_n_per_mm_per_s = positive(traction, "rate_n_per_mm_per_s");
    spec.max_n_per_mm = positive(traction, "max_n_per_mm");
    scene.tractions.push_back(spec);
  }
  if (scene.tractions.size() > 255)
    fail("{}: at most 255 [[traction]] tables", name);
  if (top.has("grasp")) {
    TomlTable grasp = top.required_table("grasp");
    grasp.only({"centre_mm", "radius_mm", "force_rate_n_per_s", "max_force_n", "inward_deg"});
    GraspSpec spec;
    spec.centre_mm = point(grasp, "centre_mm", Vec2::Zero());
    spec.radius_mm = positive(grasp, "radius_mm");
    spec.force_rate_n_per_s = positive(grasp, "force_rate_n_per_s");
    spec.max_force_n = positive(grasp, "max_force_n");
    spec.inward_rad = grasp.number("inward_deg", 0.0) * kDegree;
    scene.grasp = spec;
  }
  for (TomlTable& cut : top.tables("cut")) {
    cut.only({"points_mm", "tear_from"});
    CutSpec spec;
    spec.points_mm = points(cut, "points_mm");
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
