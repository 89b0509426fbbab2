#pragma once
/// @brief Pictures of a sweep: the ligament coloured by strain energy density with its fibers,
/// between the bones, at chosen angles (ligament paper, Figure 4), all from one camera and on
/// one colour scale; and strain energy against flexion angle.

#include "sim/flexion/flexion_output.hpp"
#include "sim/flexion/knee_flexion.hpp"

#include <Eigen/Core>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>

#include <filesystem>
#include <map>
#include <vector>

namespace ligsim::render {

class FlexionPictures {
public:
  /// `angles_deg`: the angles to draw (others are not kept).
  FlexionPictures(const sim::KneeModel& model, const sim::FlexionOutput& output,
                  const sim::FlexionAxis& axis, std::vector<double> angles_deg,
                  std::filesystem::path directory);

  /// Keeps the state, and the ligament as written in `ligament` (the file
  /// sim::FlexionOutput::write_angle returns), if `angle` is one to draw.
  void keep(const sim::AngleResult& angle, const Eigen::VectorXd& x,
            const std::filesystem::path& ligament);

  /// Renders ligament_<angle>.png for the kept states and strain_energy.png for the sweep;
  /// returns the files written. Starts a private X server when there is no display.
  std::vector<std::filesystem::path> render(const std::vector<sim::AngleResult>& angles) const;

private:
  const sim::KneeModel& m_model;
  const sim::FlexionOutput& m_output;
  sim::FlexionAxis m_axis;
  std::vector<double> m_angles;
  std::filesystem::path m_directory;
  std::map<double, Eigen::VectorXd> m_states;
  std::map<double, vtkSmartPointer<vtkUnstructuredGrid>> m_grids;
  std::map<double, std::vector<Eigen::Vector3d>> m_contacts; ///< nodes touching a bone
  std::map<double, double> m_load_factors;
};

} // namespace ligsim::render
