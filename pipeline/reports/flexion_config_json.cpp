#include "pipeline/reports/flexion_config_json.hpp"

#include "common/fields_json.hpp"
#include "sim/flexion/flexion_fields.hpp"

namespace ligsim::reports {

nlohmann::json to_json(const sim::FlexionSettings& settings)
{
  nlohmann::json json = {{"model", settings.model_dir.string()}};
  sim::visit_flexion_tables(settings, [&](const std::string& table, const auto& part, auto visit) {
    nlohmann::json& into = table.empty() ? json : json[table];
    visit(part, FieldJsonWriter{into});
  });
  json["motion"]["table"] = settings.motion.table.string();
  return json;
}

} // namespace ligsim::reports
