#include "common/knee_anatomy.hpp"

#include "common/error.hpp"
#include "common/run_summary.hpp"

#include <fstream>

namespace ligsim {

namespace {

Eigen::Vector3d vector_of(const nlohmann::json& json, const std::string& where)
{
  if (!json.is_array() || json.size() != 3 || !json[0].is_number() || !json[1].is_number() ||
      !json[2].is_number())
    fail("{}: expected three numbers, got {}", where, json.dump());
  return {json[0].get<double>(), json[1].get<double>(), json[2].get<double>()};
}

} // namespace

nlohmann::json to_json(const KneeAnatomy& anatomy)
{
  nlohmann::json json = {{"side", anatomy.side},
                         {"side_source", anatomy.side_source},
                         {"frame_source", anatomy.frame_source},
                         {"not_found", anatomy.not_found}};
  if (anatomy.proximal)
    json["proximal"] = json_vector3(*anatomy.proximal);
  if (anatomy.posterior)
    json["posterior"] = json_vector3(*anatomy.posterior);
  json["landmarks"] = nlohmann::json::object();
  for (const auto& [name, landmark] : anatomy.landmarks)
    json["landmarks"][name] = {{"point_mm", json_vector3(landmark.point_mm)},
                               {"source", landmark.source}};
  return json;
}

KneeAnatomy knee_anatomy_from_json(const nlohmann::json& json, const std::string& where)
{
  if (!json.is_object())
    fail("{}: expected a JSON object", where);
  KneeAnatomy anatomy;
  try {
    anatomy.side = json.value("side", "");
    anatomy.frame_source = json.value("frame_source", "");
    anatomy.side_source = json.value("side_source", "");
    anatomy.not_found = json.value("not_found", std::vector<std::string>{});
    if (json.contains("proximal"))
      anatomy.proximal = vector_of(json["proximal"], where + ": proximal").normalized();
    if (json.contains("posterior"))
      anatomy.posterior = vector_of(json["posterior"], where + ": posterior").normalized();
    if (json.contains("landmarks"))
      for (const auto& [name, landmark] : json["landmarks"].items())
        anatomy.landmarks[name] = {vector_of(landmark.at("point_mm"), where + ": landmark " + name),
                                   landmark.value("source", "")};
  } catch (const nlohmann::json::exception& e) {
    fail("{}: {}", where, e.what());
  }
  if (!anatomy.side.empty() && anatomy.side_sign() == 0)
    fail("{}: side must be \"left\" or \"right\", got \"{}\"", where, anatomy.side);
  return anatomy;
}

KneeAnatomy read_knee_anatomy(const std::filesystem::path& dir)
{
  const std::filesystem::path file = dir / knee_anatomy_file;
  std::ifstream in(file);
  if (!in)
    return {};
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    fail("{}: not valid JSON: {}", file.string(), e.what());
  }
  return knee_anatomy_from_json(json, file.string());
}

} // namespace ligsim
