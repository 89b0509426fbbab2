#pragma once
/// @brief Files of a flexion sweep: per angle the ligament (ligament_<angle>.vtu) and the turned
/// femur (femur_<angle>.vtp), the fixed tibia once (tibia.vtp), one flexion.pvd showing them
/// together in ParaView, the table flexion.csv and strain_energy.svg (energy against angle).

#include "common/vtk_files.hpp"
#include "sim/flexion/knee_flexion.hpp"
#include "sim/scene/scene_output.hpp"

#include <nlohmann/json.hpp>
#include <vtkUnstructuredGrid.h>

#include <filesystem>
#include <string>
#include <vector>

namespace ligsim::sim {

/// "45" for whole degrees, "22.5" otherwise: the angle in file names.
std::string angle_label(double angle_deg);
/// The step in file names: its angle, or "t" and its time for a motion in time.
std::string step_label(const AngleResult& angle);

/// One row of the sweep as JSON (summary.json's per-angle entries).
nlohmann::json angle_json(const AngleResult& angle);

class FlexionOutput {
public:
  FlexionOutput(const HyperelasticBody& body, const KneeModel& model, RigidMotion femur,
                std::filesystem::path directory);

  /// Writes the angle's files; returns the ligament as written (for the pictures).
  vtkSmartPointer<vtkUnstructuredGrid> write_angle(const AngleResult& angle,
                                                   const Eigen::VectorXd& x);
  /// Writes flexion.pvd for the angles written so far, flexion.csv and strain_energy.svg for
  /// `angles`.
  void finish(const std::vector<AngleResult>& angles) const;

  /// The femur surface in its pose at load factor t.
  vtkSmartPointer<vtkPolyData> moved_femur(double load_factor) const;

private:
  const HyperelasticBody& m_body;
  const KneeModel& m_model;
  RigidMotion m_femur;
  std::filesystem::path m_directory;
  SceneOutput m_ligament;
  std::vector<PvdDataSet> m_series;
};

} // namespace ligsim::sim
