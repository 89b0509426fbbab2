#include "pipeline/reports/config_json.hpp"

#include "common/fields_json.hpp"
#include "sim/flexion/flexion_fields.hpp"
#include "sim/membrane/scene/scene_fields.hpp"
#include "sim/scene/scene_fields.hpp"

namespace ligsim::reports {

namespace {

/// The tables a visit_*_tables list names, each written by its key list; the top level's keys
/// (the table named "") at the top.
template <class S, class VisitTables>
nlohmann::json tables_json(const S& settings, VisitTables visit_tables)
{
  nlohmann::json json = nlohmann::json::object();
  visit_tables(settings, [&](const std::string& table, const auto& part, auto visit) {
    visit(part, FieldJsonWriter{table.empty() ? json : json[table]});
  });
  return json;
}

} // namespace

nlohmann::json to_json(const sim::FlexionSettings& settings)
{
  nlohmann::json json =
      tables_json(settings, [](const auto& s, auto&& t) { sim::visit_flexion_tables(s, t); });
  json["model"] = settings.model_dir.string();
  json["motion"]["table"] = settings.motion.table.string();
  return json;
}

nlohmann::json to_json(const sim::Scene& scene)
{
  return tables_json(scene, [](const auto& s, auto&& t) { sim::visit_scene_tables(s, t); });
}

nlohmann::json to_json(const membrane::Scene& scene)
{
  return tables_json(scene, [](const auto& s, auto&& t) { membrane::visit_tear_tables(s, t); });
}

} // namespace ligsim::reports
