#include "pipeline/render/flexion_pictures.hpp"

#include "pipeline/render/ligament_picture.hpp"
#include "pipeline/render/line_plot_picture.hpp"
#include "pipeline/render/offscreen_display.hpp"

#include "common/vtk_files.hpp"
#include "stages/io/vtk_convert.hpp"

#include <Eigen/Geometry>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <cmath>

namespace ligsim::render {

namespace fs = std::filesystem;

namespace {

/// One camera for every angle: looking along the flexion axis from the ligament's side, femur
/// up, framing the ligament in all the states drawn.
PictureCamera sweep_camera(const sim::KneeModel& model, const sim::FlexionAxis& axis,
                           const std::map<double, Eigen::VectorXd>& states, int width, int height)
{
  const Eigen::Vector3d a = axis.direction.normalized();
  const Eigen::Vector3d ligament_centre = model.mesh.V.colwise().mean().transpose();
  const double side = (ligament_centre - axis.point_mm).dot(a) >= 0.0 ? 1.0 : -1.0;
  PictureCamera camera;
  camera.view_direction = -side * a;
  const Eigen::Vector3d proximal = sim::proximal_direction(model);
  Eigen::Vector3d up = proximal - proximal.dot(camera.view_direction) * camera.view_direction;
  if (up.norm() < 1e-9)
    up = camera.view_direction.unitOrthogonal();
  camera.up = up.normalized();
  const Eigen::Vector3d right = camera.view_direction.cross(camera.up);

  Eigen::Vector2d low = Eigen::Vector2d::Constant(INFINITY);
  Eigen::Vector2d high = Eigen::Vector2d::Constant(-INFINITY);
  double depth = 0.0;
  for (const auto& [angle, x] : states)
    for (Eigen::Index n = 0; n < x.size() / 3; ++n) {
      const Eigen::Vector3d p = x.segment<3>(3 * n);
      const Eigen::Vector2d screen(p.dot(right), p.dot(camera.up));
      low = low.cwiseMin(screen);
      high = high.cwiseMax(screen);
      depth += p.dot(camera.view_direction);
    }
  depth /= static_cast<double>(states.size() * static_cast<std::size_t>(model.mesh.V.rows()));
  const Eigen::Vector2d middle = 0.5 * (low + high);
  camera.focal_point_mm =
      middle.x() * right + middle.y() * camera.up + depth * camera.view_direction;
  const Eigen::Vector2d extent = high - low;
  camera.view_height_mm =
      1.25 * std::max(extent.y(), extent.x() * height / static_cast<double>(width));
  return camera;
}

} // namespace

FlexionPictures::FlexionPictures(const sim::KneeModel& model, const sim::FlexionOutput& output,
                                 const sim::FlexionAxis& axis, std::vector<double> angles_deg,
                                 fs::path directory)
    : m_model(model)
    , m_output(output)
    , m_axis(axis)
    , m_angles(std::move(angles_deg))
    , m_directory(std::move(directory))
{
}

void FlexionPictures::keep(const sim::AngleResult& angle, const Eigen::VectorXd& x,
                           const fs::path& ligament)
{
  for (double wanted : m_angles)
    if (std::abs(wanted - angle.angle_deg) < 1e-9) {
      m_states[angle.angle_deg] = x;
      m_load_factors[angle.angle_deg] = angle.load_factor;
      m_grids[angle.angle_deg] = read_vtu(ligament);
      std::vector<Eigen::Vector3d>& touching = m_contacts[angle.angle_deg];
      for (Eigen::Index n = 0; n < angle.pressure_mpa.size(); ++n)
        if (angle.pressure_mpa(n) > 0.0)
          touching.push_back(x.segment<3>(3 * n));
    }
}

std::vector<fs::path> FlexionPictures::render(const std::vector<sim::AngleResult>& angles) const
{
  std::vector<fs::path> written;
  OffscreenDisplay display;

  LigamentPicture picture;
  for (const auto& [angle, grid] : m_grids) {
    // The 95th percentile: the few tets at an attachment's edge would otherwise take the scale.
    picture.energy_max_mpa =
        std::max(picture.energy_max_mpa, strain_energy_percentile_mpa(grid, 0.95));
  }
  if (!m_states.empty()) {
    const PictureCamera camera =
        sweep_camera(m_model, m_axis, m_states, picture.width, picture.height);
    const vtkSmartPointer<vtkPolyData> tibia = io::to_polydata(*m_model.tibia);
    for (const auto& [angle, grid] : m_grids) {
      const vtkSmartPointer<vtkPolyData> femur =
          io::to_polydata(m_output.moved_femur(m_load_factors.at(angle)));
      picture.ligament = grid;
      picture.bones = {femur, tibia};
      picture.caption = "flexion " + sim::angle_label(angle) + " deg";
      picture.contact_points_mm = m_contacts.at(angle);
      const fs::path png = m_directory / ("ligament_" + sim::angle_label(angle) + ".png");
      render_ligament_png(picture, camera, png);
      written.push_back(png);
    }
  }

  LinePlot plot;
  plot.title = "Strain energy of the ligament across flexion";
  plot.x_label = "flexion angle (deg)";
  plot.y_label = "strain energy (mJ)";
  for (const sim::AngleResult& angle : angles) {
    plot.x.push_back(angle.angle_deg);
    plot.y.push_back(angle.strain_energy_mj);
  }
  if (!plot.x.empty()) {
    render_line_plot_png(plot, m_directory / "strain_energy.png");
    written.push_back(m_directory / "strain_energy.png");
  }
  return written;
}

} // namespace ligsim::render
