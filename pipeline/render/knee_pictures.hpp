#pragma once
/// @brief Pictures of a knee's sweep: at chosen angles the whole knee from the front and from the
/// medial side, every ligament coloured by fiber strain on one scale for all angles and views,
/// the bones see-through (knee_front_<angle>.png, knee_medial_<angle>.png).

#include "common/knee_anatomy.hpp"
#include "sim/flexion/axis/condyle_axis.hpp"
#include "sim/flexion/flexion_output.hpp"

#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace ligsim::render {

class KneePictures {
public:
  /// `bones`: the knee's bones (femur, tibia, fibula); `anatomy`: its directions (the front and
  /// the medial side; without them the views look across and along the flexion axis);
  /// `names`: the ligaments, in the order `keep` numbers them; `angles_deg`: the angles to draw.
  KneePictures(const sim::KneeModel& bones, const sim::FlexionOutput& output, KneeAnatomy anatomy,
               const sim::FlexionAxis& axis, std::vector<std::string> names,
               std::vector<double> angles_deg, std::filesystem::path directory);

  /// Keeps ligament `ligament`'s state as written in `written` (the file
  /// sim::FlexionOutput::write_angle returns) if `angle` is one to draw.
  void keep(std::size_t ligament, const sim::AngleResult& angle,
            const std::filesystem::path& written);

  /// Renders the kept angles (those every ligament reached); returns the files written.
  std::vector<std::filesystem::path> render() const;

private:
  const sim::KneeModel& m_bones;
  const sim::FlexionOutput& m_output;
  KneeAnatomy m_anatomy;
  sim::FlexionAxis m_axis;
  std::vector<std::string> m_names;
  std::vector<double> m_angles;
  std::filesystem::path m_directory;
  /// angle -> per ligament the grid (null where not reached)
  std::map<double, std::vector<vtkSmartPointer<vtkUnstructuredGrid>>> m_grids;
  std::map<double, double> m_load_factors;
};

} // namespace ligsim::render
