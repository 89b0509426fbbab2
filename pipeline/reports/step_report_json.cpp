#include "pipeline/reports/step_report_json.hpp"

namespace ligsim::reports {

nlohmann::json to_json(const sim::StepReport& step)
{
  nlohmann::json json = {{"step", step.step},
                         {"load_factor", step.load_factor},
                         {"converged", step.converged},
                         {"newton_iterations", step.iterations},
                         {"substeps", step.substeps},
                         {"cutbacks", step.cutbacks},
                         {"cg_iterations", step.linear_iterations},
                         {"factorizations", step.factorizations},
                         {"projected_elements", step.projected_elements},
                         {"indefinite_iterations", step.indefinite_iterations},
                         {"line_search_backtracks", step.line_search_backtracks},
                         {"saddle_iterations", step.saddle_iterations},
                         {"shifted_iterations", step.shifted_iterations},
                         {"relative_residual", step.relative_residual},
                         {"converged_at_floor", step.converged_at_floor},
                         {"negative_eigenvalues", step.negative_eigenvalues},
                         {"strain_energy_mj", step.strain_energy_mj},
                         {"min_j", step.min_j},
                         {"min_j_element", step.min_j_element},
                         {"wall_s", step.wall_s}};
  if (step.converged_at_floor)
    json["floor"] = step.floor;
  if (!step.instability.empty())
    json["instability"] = step.instability;
  return json;
}

nlohmann::json to_json(const sim::FrameReport& frame)
{
  return {{"frame", frame.frame},
          {"time_s", frame.time_s},
          {"load_factor", frame.load_factor},
          {"relative_residual", frame.relative_residual},
          {"relative_inertia", frame.relative_inertia},
          {"kinetic_energy_mj", frame.kinetic_energy_mj},
          {"strain_energy_mj", frame.strain_energy_mj},
          {"min_j", frame.min_j},
          {"min_j_element", frame.min_j_element},
          {"substeps", frame.substeps},
          {"cg_iterations", frame.linear_iterations},
          {"factorizations", frame.factorizations},
          {"wall_s", frame.wall_s}};
}

} // namespace ligsim::reports
