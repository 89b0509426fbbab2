#pragma once
/// @brief Per-step outputs of a scene: a VTU of the deformed mesh (VTK_TETRA or
/// VTK_QUADRATIC_TETRA cells; point data: displacement; cell data, a quadratic tet's the
/// volume-weighted mean over its points: "strain_energy_density" (MPa), "J", and with fibers
/// "fiber_stretch" (|F a|) and "fiber_direction" (unit, deformed)) and the .pvd series.

#include "sim/solver/hyperelastic_body.hpp"

#include <Eigen/Core>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace ligsim::sim {

/// Extra point data of a written state: name and one value per node.
using PointArrays = std::vector<std::pair<std::string, Eigen::VectorXd>>;

class SceneOutput {
public:
  SceneOutput(const HyperelasticBody& body, std::filesystem::path directory);

  /// Writes `<directory>/step_<index>.vtu` for positions `x` (mm) at `time` (load factor or
  /// seconds). Throws SolverError rather than write a non-finite value.
  void write_step(int index, double time, const Eigen::VectorXd& x, const PointArrays& extra = {});
  /// The same under any file name (relative to the directory), with `extra` point data;
  /// returns the file written.
  std::filesystem::path write(const std::string& name, double time, const Eigen::VectorXd& x,
                              const PointArrays& extra = {});

  /// Writes `<directory>/<pvd>` listing every step written.
  void finish(const std::string& pvd = "series.pvd");

  const std::vector<std::pair<double, std::string>>& written() const { return m_steps; }

private:
  const HyperelasticBody& m_body;
  std::filesystem::path m_directory;
  std::vector<std::pair<double, std::string>> m_steps;
};

} // namespace ligsim::sim
