#include "pipeline/reports/verify_reports.hpp"

#include "pipeline/reports/knee_reports.hpp"

#include <cmath>

namespace ligsim::reports {

nlohmann::json to_json(const std::vector<sim::CubeCaseResult>& results)
{
  nlohmann::json cases = nlohmann::json::array();
  for (const sim::CubeCaseResult& r : results) {
    nlohmann::json entry = {{"name", r.name},
                            {"energy", sim::to_string(r.energy)},
                            {"avg_error_pct", r.avg_error_pct},
                            {"max_error_pct", r.max_error_pct},
                            {"avg_error_all_pct", r.avg_error_all_pct},
                            {"max_error_all_pct", r.max_error_all_pct},
                            {"avg_fiber_strain_pct", r.avg_fiber_strain_pct},
                            {"volume_change_pct", r.volume_change_pct},
                            {"wall_s", r.wall_s},
                            {"cpu_s", r.cpu_s},
                            {"febio_wall_s", r.febio_wall_s},
                            {"converged", r.converged},
                            {"incompressibility", r.incompressibility},
                            {"avg_top_uz_mm", r.avg_top_uz_mm},
                            {"newton_iterations", r.newton_iterations},
                            {"factorizations", r.factorizations},
                            {"cg_iterations", r.cg_iterations},
                            {"load_steps", r.load_steps},
                            {"projected_elements", r.projected_elements},
                            {"relative_residual", r.relative_residual},
                            {"balance_error", r.balance_error},
                            {"substeps", r.substeps},
                            {"cutbacks", r.cutbacks},
                            {"saddle_iterations", r.saddle_iterations},
                            {"converged_at_floor", r.converged_at_floor},
                            {"negative_eigenvalues", r.negative_eigenvalues}};
    if (r.converged_at_floor)
      entry["floor"] = r.floor;
    if (!r.instability.empty())
      entry["instability"] = r.instability;
    if (!r.converged) {
      entry["failure"] = r.failure;
      for (const char* key :
           {"avg_error_pct", "max_error_pct", "avg_error_all_pct", "max_error_all_pct",
            "avg_fiber_strain_pct", "volume_change_pct", "avg_top_uz_mm"})
        entry[key] = nullptr;
    }
    cases.push_back(entry);
  }
  return {{"cases", cases}};
}

nlohmann::json to_json(const std::vector<sim::StabilityResult>& results)
{
  nlohmann::json cases = nlohmann::json::array();
  for (const sim::StabilityResult& r : results)
    cases.push_back({{"name", r.name},
                     {"description", r.description},
                     {"outcome", sim::to_string(r.outcome)},
                     {"converged", r.converged},
                     {"diagnostic", r.diagnostic},
                     {"iterations", r.iterations},
                     {"wall_s", r.wall_s},
                     {"min_j", std::isfinite(r.min_j) ? nlohmann::json(r.min_j) : nullptr},
                     {"balance_error", r.balance_error},
                     {"max_displacement_mm", r.max_displacement_mm}});
  return {{"cases", cases}};
}

nlohmann::json to_json(const std::vector<sim::FlexionCaseResult>& results)
{
  auto number = [](double value) {
    return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json("not measured");
  };
  nlohmann::json cases = nlohmann::json::array();
  for (const sim::FlexionCaseResult& r : results) {
    nlohmann::json angles = nlohmann::json::array();
    for (const sim::AngleResult& angle : r.angles)
      angles.push_back(to_json(angle));
    cases.push_back(
        {{"name", r.name},
         {"description", r.description},
         {"model", r.model},
         {"tets", r.tets},
         {"model_change", r.model_change},
         {"outcome", sim::to_string(r.outcome)},
         {"diagnostic", r.diagnostic},
         {"target_angle_deg", r.target_angle_deg},
         {"angles_reached", r.angles.size()},
         {"last_angle_deg",
          r.angles.empty() ? nlohmann::json("none") : nlohmann::json(r.angles.back().angle_deg)},
         {"iterations", r.iterations},
         {"wall_s", r.wall_s},
         {"max_fiber_strain", r.max_fiber_strain},
         {"min_j", number(r.min_j)},
         {"equilibrium_residual", number(r.equilibrium_residual)},
         {"non_finite", r.non_finite},
         {"angles", angles}});
  }
  return {{"cases", cases}};
}

} // namespace ligsim::reports
