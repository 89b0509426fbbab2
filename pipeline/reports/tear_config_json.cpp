#include "pipeline/reports/tear_config_json.hpp"

#include "common/fields_json.hpp"
#include "sim/membrane/scene/scene_fields.hpp"

namespace ligsim::reports {

nlohmann::json to_json(const membrane::Scene& scene)
{
  nlohmann::json json = nlohmann::json::object();
  membrane::visit_tear_tables(scene, [&](const std::string& table, const auto& part, auto visit) {
    visit(part, FieldJsonWriter{json[table]});
  });
  return json;
}

} // namespace ligsim::reports
