#include "pipeline/reports/scene_config_json.hpp"

#include "common/fields_json.hpp"
#include "sim/scene/scene_fields.hpp"

namespace ligsim::reports {

nlohmann::json to_json(const sim::Scene& scene)
{
  nlohmann::json json = nlohmann::json::object();
  sim::visit_scene_tables(scene, [&](const std::string& table, const auto& part, auto visit) {
    visit(part, FieldJsonWriter{json[table]});
  });
  return json;
}

} // namespace ligsim::reports
