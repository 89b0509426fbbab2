#include "common/run_summary.hpp"

#include "common/atomic_file.hpp"
#include "common/resources.hpp"

namespace ligsim {

nlohmann::json json_vector3(const Eigen::Vector3d& v)
{
  return {v.x(), v.y(), v.z()};
}

RunSummary::RunSummary(std::string job)
{
  m_json["job"] = std::move(job);
  m_json["ligsim_version"] = "0.1.0";
  m_json["inputs"] = nlohmann::json::object();
  m_json["parameters"] = nlohmann::json::object();
  m_json["stages"] = nlohmann::json::object();
  m_json["results"] = nlohmann::json::object();
}

nlohmann::json& RunSummary::stage(const std::string& name)
{
  return m_json["stages"][name];
}

nlohmann::json& RunSummary::add_stage(const std::string& name, const StageMeter& meter,
                                      nlohmann::json figures)
{
  nlohmann::json& entry = stage(name);
  if (!figures.is_null())
    entry.update(figures);
  entry["wall_s"] = meter.wall_s();
  entry["peak_rss_mib"] = meter.peak_rss_mib();
  return entry;
}

void RunSummary::write(const std::filesystem::path& dir)
{
  double total = 0.0;
  for (const auto& [name, entry] : m_json["stages"].items())
    if (entry.contains("wall_s") && entry["wall_s"].is_number())
      total += entry["wall_s"].get<double>();
  m_json["total_stage_wall_s"] = total;
  ensure_directory(dir);
  write_text_atomically(dir / "summary.json", m_json.dump(2) + "\n");
}

} // namespace ligsim
