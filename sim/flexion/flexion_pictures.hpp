#pragma once
/// @brief Pictures of a sweep: the ligament coloured by strain energy density with its fibers,
/// between the bones, at chosen angles (ligament paper, Figure 4), all from one camera and on
/// one colour scale; and strain energy against flexion angle.

#include "sim/flexion/flexion_output.hpp"
#include "sim/flexion/knee_flexion.hpp"

#include <Eigen/Core>

#include <filesystem>
#include <map>
#include <vector>

namespace ligsim::sim {

class FlexionPictures {
public:
  /// `angles_deg`: the angles to draw (others are not kept).
  FlexionPictures(const HyperelasticBody& body, const KneeModel& model, const FlexionOutput& output,
                  const FlexionAxis& axis, std::vector<double> angles_deg,
                  std::filesystem::path directory);

  /// Keeps the state if `angle` is one to draw.
  void keep(const AngleResult& angle, const Eigen::VectorXd& x);

  /// Renders ligament_<angle>.png for the kept states and strain_energy.png for the sweep;
  /// returns the files written. Starts a private X server when there is no display.
  std::vector<std::filesystem::path> render(const std::vector<AngleResult>& angles) const;

private:
  const HyperelasticBody& m_body;
  const KneeModel& m_model;
  const FlexionOutput& m_output;
  FlexionAxis m_axis;
  std::vector<double> m_angles;
  std::filesystem::path m_directory;
  std::map<double, Eigen::VectorXd> m_states;
};

} // namespace ligsim::sim
