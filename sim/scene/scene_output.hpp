#pragma once
/// @brief Per-step outputs of a scene: a VTU of the deformed mesh (point data: displacement;
/// cell data: strain energy density, J, fiber stretch and direction) and the .pvd series.

#include "sim/solver/hyperelastic_body.hpp"

#include <Eigen/Core>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace ligsim::sim {

class SceneOutput {
public:
  SceneOutput(const HyperelasticBody& body, std::filesystem::path directory);

  /// Writes `<directory>/step_<index>.vtu` for positions `x` (mm) at `time` (load factor or
  /// seconds). Throws SolverError rather than write a non-finite value.
  void write_step(int index, double time, const Eigen::VectorXd& x);

  /// Writes `<directory>/series.pvd` listing every step written.
  void finish();

  const std::vector<std::pair<double, std::string>>& written() const { return m_steps; }

private:
  const HyperelasticBody& m_body;
  std::filesystem::path m_directory;
  std::vector<std::pair<double, std::string>> m_steps;
};

} // namespace ligsim::sim
