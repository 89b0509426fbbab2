#include "sim/flexion/flexion_output.hpp"

#include "common/atomic_file.hpp"
#include "common/run_summary.hpp"
#include "common/svg_plot.hpp"
#include "common/vtk_files.hpp"
#include "stages/io/vtk_convert.hpp"

#include <fmt/format.h>
#include <vtkPolyData.h>

#include <cmath>
#include <map>

namespace ligsim::sim {

namespace fs = std::filesystem;

std::string angle_label(double angle_deg)
{
  if (std::abs(angle_deg - std::round(angle_deg)) < 1e-9)
    return fmt::format("{}", static_cast<long>(std::lround(angle_deg)));
  return fmt::format("{:g}", angle_deg);
}

std::string step_label(const AngleResult& angle)
{
  return std::isnan(angle.time_s) ? angle_label(angle.angle_deg) : "t" + angle_label(angle.time_s);
}

FlexionOutput::FlexionOutput(std::vector<OutputLigament> ligaments, const KneeModel& bones,
                             RigidMotion femur, fs::path directory)
    : m_ligaments(std::move(ligaments))
    , m_femur_surface(bones.femur)
    , m_tibia(bones.tibia)
    , m_fibula(bones.fibula)
    , m_femur(std::move(femur))
    , m_directory(std::move(directory))
{
  write_vtk(io::to_polydata(*m_tibia), m_directory / "tibia.vtp");
  if (m_fibula)
    write_vtk(io::to_polydata(*m_fibula), m_directory / "fibula.vtp");
  for (const OutputLigament& ligament : m_ligaments)
    if (!ligament.folder.empty())
      ensure_directory(m_directory / ligament.folder);
}

TriangleSurface FlexionOutput::moved_femur(double load_factor) const
{
  const Eigen::Isometry3d pose = m_femur.pose(load_factor);
  TriangleSurface femur = *m_femur_surface;
  femur.V = (femur.V * pose.linear().transpose()).rowwise() + pose.translation().transpose();
  return femur;
}

fs::path FlexionOutput::write_angle(std::size_t ligament, const HyperelasticBody& body,
                                    const AngleResult& angle, const Eigen::VectorXd& x)
{
  const std::string label = step_label(angle);
  const fs::path folder = m_ligaments.at(ligament).folder;
  const std::string file = (folder / ("ligament_" + label + ".vtu")).string();
  PointArrays contact;
  if (angle.gap_mm.size() > 0)
    contact = {{"gap_mm", angle.gap_mm}, {"contact_pressure", angle.pressure_mpa}};
  const fs::path written = SceneOutput(body, m_directory).write(file, angle.angle_deg, x, contact);
  // ParaView's time: the angle, or the time of a motion in time.
  const double time = std::isnan(angle.time_s) ? angle.angle_deg : angle.time_s;
  m_series.push_back({time, static_cast<int>(ligament), file});
  const std::string femur = "femur_" + label + ".vtp";
  if (m_femurs_written.insert(femur).second) {
    write_vtk(io::to_polydata(moved_femur(angle.load_factor)), m_directory / femur);
    const int bones = static_cast<int>(m_ligaments.size());
    m_series.push_back({time, bones, femur});
    m_series.push_back({time, bones + 1, "tibia.vtp"});
    if (m_fibula)
      m_series.push_back({time, bones + 2, "fibula.vtp"});
  }
  return written;
}

void FlexionOutput::finish(const std::vector<std::vector<AngleResult>>& angles) const
{
  if (!m_series.empty())
    write_pvd(m_directory / "flexion.pvd", m_series);
  const bool fibula = m_fibula != nullptr;
  std::string csv = "ligament,angle_deg,strain_energy_mj,converged,max_fiber_stretch,"
                    "mean_fiber_stretch,femur_force_n,tibia_force_n,newton_iterations,substeps,"
                    "relative_residual,min_j,wall_s,femur_contact_n,tibia_contact_n,"
                    "femur_contact_area_mm2,tibia_contact_area_mm2,max_penetration_mm,"
                    "mean_fiber_strain,max_fiber_strain,volume_beyond_failure_strain,"
                    "length_change_mm,length_change_pct,time_s,max_regional_fiber_strain";
  csv += fibula ? ",fibula_force_n,fibula_contact_n,fibula_contact_area_mm2" : "";
  csv += ",femur_net_force_n,femur_force_error_n,max_regional_fiber_strain_error\n";
  const auto number = [](double value) {
    return std::isnan(value) ? std::string() : fmt::format("{:.6g}", value);
  };
  for (std::size_t l = 0; l < angles.size(); ++l) {
    const OutputLigament& ligament = m_ligaments.at(l);
    for (const AngleResult& a : angles[l]) {
      // The distal footprint's force goes to its bone's column; the other bone's stays empty.
      const std::string distal = fmt::format("{:.9g}", a.tibia_force_n.norm());
      const bool on_tibia = ligament.distal_bone == "tibia";
      csv += fmt::format("{},{:g},{:.9g},{},{:.9g},{:.9g},{:.9g},{},{},{},{:.3g},{:.6g},{:.4f}",
                         ligament.name, a.angle_deg, a.strain_energy_mj, a.converged ? 1 : 0,
                         a.max_fiber_stretch, a.mean_fiber_stretch, a.femur_force_n.norm(),
                         on_tibia ? distal : "", a.newton_iterations, a.substeps,
                         a.relative_residual, a.min_j, a.wall_s);
      // Contact columns stay empty where contact is off or the bone takes none.
      std::map<std::string, std::pair<std::string, std::string>> contact;
      std::string penetration;
      double deepest = 0.0;
      for (const BoneContact& bone : a.contact) {
        if (bone.in_solve)
          contact[bone.bone] = {fmt::format("{:.9g}", bone.force_n.norm()),
                                fmt::format("{:.6g}", bone.area_mm2)};
        deepest = std::max(deepest, bone.penetration_mm);
        penetration = fmt::format("{:.4g}", deepest);
      }
      csv += fmt::format(",{},{},{},{},{}", contact["femur"].first, contact["tibia"].first,
                         contact["femur"].second, contact["tibia"].second, penetration);
      csv += fmt::format(",{:.6g},{:.6g},{:.6g},{},{},{}", a.mean_fiber_stretch - 1.0,
                         a.max_fiber_stretch - 1.0, a.failed_volume_fraction,
                         number(a.length_change_mm), number(a.length_change_pct), number(a.time_s));
      csv += "," + number(a.max_regional_fiber_stretch - 1.0);
      if (fibula)
        csv += fmt::format(",{},{},{}", on_tibia ? "" : distal, contact["fibula"].first,
                           contact["fibula"].second);
      csv += fmt::format(",{:.9g},{},{}\n", femur_net_force(a).norm(),
                         number(a.error.femur_force_n), number(a.error.regional_fiber_strain));
    }
  }
  write_text_atomically(m_directory / "flexion.csv", csv);

  PlotSpec plot;
  plot.title = m_ligaments.size() > 1 ? "Strain energy of the ligaments across flexion"
                                      : "Strain energy of the ligament across flexion";
  plot.x_label = "flexion angle (deg)";
  plot.y_label = "strain energy (mJ)";
  for (std::size_t l = 0; l < angles.size(); ++l) {
    PlotSeries series;
    series.name = m_ligaments.size() > 1 ? m_ligaments[l].name : "strain energy";
    for (const AngleResult& a : angles[l]) {
      series.x.push_back(a.angle_deg);
      series.y.push_back(a.strain_energy_mj);
    }
    plot.series.push_back(series);
  }
  write_text_atomically(m_directory / "strain_energy.svg", svg_line_plot(plot));
}

} // namespace ligsim::sim
