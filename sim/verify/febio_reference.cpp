#include "sim/verify/febio_reference.hpp"

#include "common/error.hpp"

#include <nlohmann/json.hpp>

#include <fstream>
#include <limits>
#include <sstream>

namespace ligsim::sim {

namespace {

nlohmann::json read_json(const std::filesystem::path& file)
{
  std::ifstream in(file);
  if (!in)
    fail("cannot open {}", file.string());
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    fail("{}: not valid JSON: {}", file.string(), e.what());
  }
}

template <class T> T field(const nlohmann::json& object, const char* key, const std::string& where)
{
  if (!object.contains(key))
    fail("{}: missing field \"{}\"", where, key);
  try {
    return object.at(key).get<T>();
  } catch (const nlohmann::json::exception&) {
    fail("{}: field \"{}\" has the wrong type", where, key);
  }
}

Eigen::Vector3d vector3(const nlohmann::json& object, const char* key, const std::string& where)
{
  const auto values = field<std::vector<double>>(object, key, where);
  if (values.size() != 3)
    fail("{}: field \"{}\" must have 3 components", where, key);
  return {values[0], values[1], values[2]};
}

std::vector<int> read_id_line(std::istream& in, int count, const std::string& where)
{
  std::vector<int> ids(static_cast<std::size_t>(count));
  for (int& id : ids) {
    if (!(in >> id))
      fail("{}: truncated node list", where);
    --id;
  }
  return ids;
}

} // namespace

FebioReference read_febio_reference(const std::filesystem::path& directory)
{
  const std::filesystem::path file = directory / "cases.json";
  const nlohmann::json root = read_json(file);
  const std::string where = file.string();
  FebioReference reference;
  reference.directory = directory;
  reference.edge_mm = field<double>(root, "edge_mm", where);
  reference.mesh_file = directory / field<std::string>(root, "mesh", where);
  if (!root.contains("cases") || !root["cases"].is_array() || root["cases"].empty())
    fail("{}: \"cases\" must be a non-empty list", where);
  for (const nlohmann::json& entry : root["cases"]) {
    FebioCase c;
    c.name = field<std::string>(entry, "name", where);
    const std::string at = where + ", case " + c.name;
    c.fiber = vector3(entry, "fiber", at);
    c.force_per_top_node_n = vector3(entry, "force_per_top_node_n", at);
    const nlohmann::json material = field<nlohmann::json>(entry, "material", at);
    c.material.mu_mpa = field<double>(material, "mu_mpa", at);
    c.material.bulk_modulus_mpa = field<double>(material, "k_mpa", at);
    c.material.volumetric =
        parse_volumetric_law(field<std::string>(material, "volumetric", at), at);
    FiberParameters fiber;
    fiber.c3_mpa = field<double>(material, "c3_mpa", at);
    fiber.c4 = field<double>(material, "c4", at);
    fiber.c5_mpa = field<double>(material, "c5_mpa", at);
    fiber.lambda_star = field<double>(material, "lam_star", at);
    fiber.convention =
        parse_fiber_convention(field<std::string>(material, "fiber_convention", at), at);
    c.material.fiber = fiber;
    validate(c.material);
    c.incompressibility = field<std::string>(entry, "incompressibility", at);
    c.displacements = directory / field<std::string>(entry, "displacements", at);
    if (const auto febio = entry.find("febio"); febio != entry.end() && febio->is_object()) {
      const auto figure = [&](const char* key) -> std::optional<double> {
        const auto value = febio->find(key);
        return value != febio->end() && value->is_number() ? std::optional(value->get<double>())
                                                           : std::nullopt;
      };
      c.febio = {figure("wall_s"), figure("avg_top_uz"), figure("volume_change_rel")};
    }
    reference.cases.push_back(std::move(c));
  }
  return reference;
}

FebioMesh read_febio_mesh(const std::filesystem::path& file)
{
  std::ifstream in(file);
  if (!in)
    fail("cannot open {}", file.string());
  const std::string where = file.string();
  FebioMesh result;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#')
      continue;
    std::istringstream header(line);
    std::string section;
    int count = 0;
    if (!(header >> section >> count) || count < 0)
      fail("{}: unexpected line \"{}\"", where, line);
    if (section == "NODES") {
      result.mesh.V.resize(count, 3);
      for (int n = 0; n < count; ++n) {
        int id = 0;
        if (!(in >> id >> result.mesh.V(n, 0) >> result.mesh.V(n, 1) >> result.mesh.V(n, 2)) ||
            id != n + 1)
          fail("{}: node {} is missing or out of order", where, n + 1);
      }
    } else if (section == "ELEMENTS") {
      result.mesh.T.resize(count, 4);
      for (int e = 0; e < count; ++e) {
        int id = 0;
        if (!(in >> id >> result.mesh.T(e, 0) >> result.mesh.T(e, 1) >> result.mesh.T(e, 2) >>
              result.mesh.T(e, 3)))
          fail("{}: element {} is missing", where, e + 1);
        result.mesh.T.row(e).array() -= 1;
      }
    } else if (section == "BOTTOM_NODES") {
      result.bottom_nodes = read_id_line(in, count, where);
    } else if (section == "TOP_NODES") {
      result.top_nodes = read_id_line(in, count, where);
    } else {
      fail("{}: unknown section {}", where, section);
    }
    std::getline(in, line); // rest of the last data line
  }
  if (result.mesh.V.rows() == 0 || result.mesh.T.rows() == 0 || result.bottom_nodes.empty() ||
      result.top_nodes.empty())
    fail("{}: NODES, ELEMENTS, BOTTOM_NODES and TOP_NODES are all required", where);
  return result;
}

Points read_febio_displacements(const std::filesystem::path& file, Eigen::Index node_count)
{
  std::ifstream in(file);
  if (!in)
    fail("cannot open {}", file.string());
  Points u = Points::Constant(node_count, 3, std::numeric_limits<double>::quiet_NaN());
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#')
      continue;
    std::istringstream values(line);
    long id = 0;
    double x = 0, y = 0, z = 0;
    if (!(values >> id >> x >> y >> z) || id < 1 || id > node_count)
      fail("{}: bad line \"{}\"", file.string(), line);
    u.row(id - 1) << x, y, z;
  }
  if (!u.allFinite())
    fail("{}: displacements missing for some of the {} nodes", file.string(), node_count);
  return u;
}

} // namespace ligsim::sim
