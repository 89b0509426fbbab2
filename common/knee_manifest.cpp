#include "common/knee_manifest.hpp"

#include "common/error.hpp"

#include <fstream>
#include <set>

namespace ligsim {

nlohmann::json to_json(const KneeManifest& manifest)
{
  nlohmann::json ligaments = nlohmann::json::array();
  for (const KneeLigament& l : manifest.ligaments)
    ligaments.push_back({{"name", l.name},
                         {"folder", l.folder},
                         {"distal_bone", l.distal_bone},
                         {"in_situ_strain", l.in_situ_strain},
                         {"failure_strain", l.failure_strain},
                         {"failure_load_n", l.failure_load_n},
                         {"material", l.material},
                         {"defaults_source", l.defaults_source},
                         {"contact_bones", l.contact_bones}});
  return {{"ligaments", ligaments}, {"bones", manifest.bones}};
}

KneeManifest knee_manifest_from_json(const nlohmann::json& json, const std::string& where)
{
  KneeManifest manifest;
  try {
    for (const auto& [name, file] : json.at("bones").items())
      manifest.bones[name] = file.get<std::string>();
    std::set<std::string> names;
    for (const nlohmann::json& entry : json.at("ligaments")) {
      KneeLigament l;
      l.name = entry.at("name").get<std::string>();
      l.folder = entry.at("folder").get<std::string>();
      l.distal_bone = entry.at("distal_bone").get<std::string>();
      l.in_situ_strain = entry.at("in_situ_strain").get<double>();
      l.failure_strain = entry.at("failure_strain").get<double>();
      l.failure_load_n = entry.at("failure_load_n").get<double>();
      l.material = entry.at("material");
      l.defaults_source = entry.value("defaults_source", "");
      l.contact_bones = entry.value("contact_bones", std::vector<std::string>{});
      for (const std::string& bone : l.contact_bones)
        if (!manifest.bones.count(bone))
          fail("{}: ligament {} meets the {} by contact, which the knee does not list", where,
               l.name, bone);
      if (l.name.empty() || l.folder.empty())
        fail("{}: a ligament without a name or a folder", where);
      if (l.distal_bone != "tibia" && l.distal_bone != "fibula")
        fail("{}: ligament {}: distal_bone must be \"tibia\" or \"fibula\", got \"{}\"", where,
             l.name, l.distal_bone);
      if (!manifest.bones.count(l.distal_bone))
        fail("{}: ligament {} attaches to the {}, which the knee does not list", where, l.name,
             l.distal_bone);
      if (!names.insert(l.name).second)
        fail("{}: two ligaments are called {}", where, l.name);
      manifest.ligaments.push_back(std::move(l));
    }
  } catch (const nlohmann::json::exception& e) {
    fail("{}: {}", where, e.what());
  }
  if (manifest.ligaments.empty())
    fail("{}: the knee lists no ligament", where);
  // A knee without a femur (its label map names none) is built, not flexed: the flexion says so.
  if (!manifest.bones.count("tibia"))
    fail("{}: the knee lists no tibia", where);
  return manifest;
}

std::optional<KneeManifest> read_knee_manifest(const std::filesystem::path& dir)
{
  const std::filesystem::path file = dir / knee_manifest_file;
  std::ifstream in(file);
  if (!in)
    return std::nullopt;
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    fail("{}: not valid JSON: {}", file.string(), e.what());
  }
  return knee_manifest_from_json(json, file.string());
}

} // namespace ligsim
