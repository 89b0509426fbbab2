#include "pipeline/render/knee_pictures.hpp"

#include "pipeline/render/knee_picture.hpp"
#include "pipeline/render/offscreen_display.hpp"

#include "common/vtk_files.hpp"
#include "stages/io/vtk_convert.hpp"

#include <Eigen/Geometry>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>

namespace ligsim::render {

namespace fs = std::filesystem;

namespace {

/// Unit `v` without its part along unit `axis`.
Eigen::Vector3d across(const Eigen::Vector3d& v, const Eigen::Vector3d& axis)
{
  return (v - v.dot(axis) * axis).normalized();
}

/// One camera for every angle of a view: `view` from the camera into the scene, `up` on the
/// screen, framing every ligament kept.
PictureCamera frame(const std::vector<vtkUnstructuredGrid*>& grids, const Eigen::Vector3d& view,
                    const Eigen::Vector3d& up, int width, int height)
{
  PictureCamera camera;
  camera.view_direction = view;
  camera.up = across(up, view);
  const Eigen::Vector3d right = camera.view_direction.cross(camera.up);
  Eigen::Vector2d low = Eigen::Vector2d::Constant(INFINITY);
  Eigen::Vector2d high = Eigen::Vector2d::Constant(-INFINITY);
  double depth = 0.0;
  long count = 0;
  for (vtkUnstructuredGrid* grid : grids)
    for (vtkIdType p = 0; p < grid->GetNumberOfPoints(); ++p) {
      Eigen::Vector3d x;
      grid->GetPoints()->GetPoint(p, x.data());
      const Eigen::Vector2d screen(x.dot(right), x.dot(camera.up));
      low = low.cwiseMin(screen);
      high = high.cwiseMax(screen);
      depth += x.dot(view);
      ++count;
    }
  const Eigen::Vector2d middle = 0.5 * (low + high);
  camera.focal_point_mm = middle.x() * right + middle.y() * camera.up +
                          depth / static_cast<double>(std::max(count, 1L)) * view;
  const Eigen::Vector2d extent = high - low;
  // Room around the ligaments for the bones they attach to, and for the colour bar on the right.
  camera.view_height_mm =
      1.6 * std::max(extent.y(), 1.3 * extent.x() * height / static_cast<double>(width));
  return camera;
}

} // namespace

KneePictures::KneePictures(const sim::KneeModel& bones, const sim::FlexionOutput& output,
                           KneeAnatomy anatomy, const sim::FlexionAxis& axis,
                           std::vector<std::string> names, std::vector<double> angles_deg,
                           fs::path directory)
    : m_bones(bones)
    , m_output(output)
    , m_anatomy(std::move(anatomy))
    , m_axis(axis)
    , m_names(std::move(names))
    , m_angles(std::move(angles_deg))
    , m_directory(std::move(directory))
{
}

void KneePictures::keep(std::size_t ligament, const sim::AngleResult& angle,
                        const fs::path& written)
{
  for (double wanted : m_angles)
    if (std::abs(wanted - angle.angle_deg) < 1e-9) {
      auto& grids = m_grids[angle.angle_deg];
      grids.resize(m_names.size());
      grids.at(ligament) = read_vtu(written);
      m_load_factors[angle.angle_deg] = angle.load_factor;
    }
}

std::vector<fs::path> KneePictures::render() const
{
  // The angles every ligament reached, and the scale over all of them.
  std::map<double, std::vector<vtkUnstructuredGrid*>> complete;
  std::vector<vtkUnstructuredGrid*> all;
  for (const auto& [angle, grids] : m_grids) {
    std::vector<vtkUnstructuredGrid*> raw;
    for (const auto& grid : grids)
      if (grid)
        raw.push_back(grid);
    if (raw.size() != m_names.size())
      continue;
    complete[angle] = raw;
    all.insert(all.end(), raw.begin(), raw.end());
  }
  if (complete.empty())
    return {};

  // Directions: up the leg, the front, and the lateral side (the medial view looks toward it).
  const Eigen::Vector3d up =
      m_anatomy.proximal ? *m_anatomy.proximal : sim::proximal_direction(m_bones);
  const Eigen::Vector3d along_axis = across(m_axis.direction.normalized(), up);
  const Eigen::Vector3d anterior = m_anatomy.posterior
                                       ? Eigen::Vector3d(-across(*m_anatomy.posterior, up))
                                       : Eigen::Vector3d(up.cross(along_axis));
  Eigen::Vector3d lateral = along_axis;
  if (m_anatomy.posterior && m_anatomy.side_sign() != 0)
    lateral = m_anatomy.side_sign() * anterior.cross(up); // the subject's right, or left
  KneePicture picture;
  picture.strain_min = std::min(0.0, fiber_strain_percentile(all, 0.01));
  picture.strain_max = std::max(0.01, fiber_strain_percentile(all, 0.99));
  picture.names = m_names;
  struct View {
    std::string name, caption;
    PictureCamera camera;
  };
  const std::vector<View> views = {
      {"front", "front", frame(all, -anterior, up, picture.width, picture.height)},
      {"medial", m_anatomy.side_sign() != 0 ? "medial side" : "along the flexion axis",
       frame(all, lateral, up, picture.width, picture.height)}};

  OffscreenDisplay display;
  std::vector<fs::path> written;
  const vtkSmartPointer<vtkPolyData> tibia = io::to_polydata(*m_bones.tibia);
  const vtkSmartPointer<vtkPolyData> fibula =
      m_bones.fibula ? io::to_polydata(*m_bones.fibula) : nullptr;
  for (const auto& [angle, grids] : complete) {
    const vtkSmartPointer<vtkPolyData> femur =
        io::to_polydata(m_output.moved_femur(m_load_factors.at(angle)));
    picture.ligaments = grids;
    picture.bones = {femur, tibia};
    if (fibula)
      picture.bones.push_back(fibula);
    for (const View& view : views) {
      picture.caption = "flexion " + sim::angle_label(angle) + " deg, " + view.caption;
      const fs::path png =
          m_directory / ("knee_" + view.name + "_" + sim::angle_label(angle) + ".png");
      render_knee_png(picture, view.camera, png);
      written.push_back(png);
    }
  }
  return written;
}

} // namespace ligsim::render
