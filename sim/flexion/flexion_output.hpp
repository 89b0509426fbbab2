#pragma once
/// @brief Files of a flexion sweep: per angle each ligament (ligament_<angle>.vtu, in the
/// ligament's folder for a knee) and the turned femur (femur_<angle>.vtp), the fixed tibia and
/// fibula once (tibia.vtp, fibula.vtp), one flexion.pvd showing them together in ParaView, the
/// table flexion.csv (a row per ligament and angle) and strain_energy.svg (energy against angle).

#include "common/pvd_file.hpp"
#include "sim/flexion/knee_flexion.hpp"
#include "sim/scene/scene_output.hpp"

#include <filesystem>
#include <set>
#include <string>
#include <vector>

namespace ligsim::sim {

/// "45" for whole degrees, "22.5" otherwise: the angle in file names.
std::string angle_label(double angle_deg);
/// The step in file names: its angle, or "t" and its time for a motion in time.
std::string step_label(const AngleResult& angle);

/// One ligament of the output.
struct OutputLigament {
  std::string name;
  std::string folder;                ///< its files, relative to the output folder ("": in it)
  std::string distal_bone = "tibia"; ///< "tibia" or "fibula"
};

class FlexionOutput {
public:
  /// The ligaments' files in their folders; the bones of `bones` (the femur turned by `femur`,
  /// the tibia and the fibula fixed) in `directory`.
  FlexionOutput(std::vector<OutputLigament> ligaments, const KneeModel& bones, RigidMotion femur,
                std::filesystem::path directory);

  /// Writes ligament `ligament`'s state at the angle (ligament_<angle>.vtu in its folder) and the
  /// femur at the angle if not yet written; returns the ligament's file (for the pictures).
  std::filesystem::path write_angle(std::size_t ligament, const HyperelasticBody& body,
                                    const AngleResult& angle, const Eigen::VectorXd& x);
  /// Writes flexion.pvd for the angles written so far, and flexion.csv (a row per ligament and
  /// angle) and strain_energy.svg for `angles`, one list per ligament.
  void finish(const std::vector<std::vector<AngleResult>>& angles) const;

  /// The femur surface in its pose at load factor t.
  TriangleSurface moved_femur(double load_factor) const;

private:
  std::vector<OutputLigament> m_ligaments;
  BoneSurface m_femur_surface, m_tibia, m_fibula;
  RigidMotion m_femur;
  std::filesystem::path m_directory;
  std::vector<PvdDataSet> m_series;
  std::set<std::string> m_femurs_written;
};

} // namespace ligsim::sim
