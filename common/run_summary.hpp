#pragma once
/// @brief summary.json: what a job read, with which parameters, what each stage cost and produced.

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

namespace ligsim {

/// [x, y, z] for summary.json.
nlohmann::json json_vector3(const Eigen::Vector3d& v);

class StageMeter;

class RunSummary {
public:
  /// `job` is the subcommand ("build", "simulate", "tear").
  explicit RunSummary(std::string job);

  nlohmann::json& inputs() { return m_json["inputs"]; }
  nlohmann::json& parameters() { return m_json["parameters"]; }
  /// Free-form results of the job as a whole (counts, quality figures).
  nlohmann::json& results() { return m_json["results"]; }

  /// Records a stage: its wall time and peak memory from `meter`, plus its own figures.
  /// Returns the stage's entry so callers can add to it.
  nlohmann::json& add_stage(const std::string& name, const StageMeter& meter,
                            nlohmann::json figures = nlohmann::json::object());

  /// The stage's entry, created if absent.
  nlohmann::json& stage(const std::string& name);

  const nlohmann::json& json() const { return m_json; }

  /// Writes `<dir>/summary.json` atomically, with the total wall time and the process peak memory.
  void write(const std::filesystem::path& dir);

private:
  nlohmann::json m_json;
};

} // namespace ligsim
