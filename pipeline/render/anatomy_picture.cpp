#include "pipeline/render/anatomy_picture.hpp"

#include "common/error.hpp"
#include "pipeline/render/ligament_picture.hpp"
#include "pipeline/render/picture_parts.hpp"
#include "pipeline/render/window_png.hpp"

#include <Eigen/Geometry>
#include <vtkActor.h>
#include <vtkBillboardTextActor3D.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSphereSource.h>
#include <vtkTextProperty.h>

#include <cmath>

namespace ligsim::render {

namespace {

/// Distinct colours for the landmarks, in order (RGB in [0, 1]).
Eigen::Vector3d colour_of(std::size_t i)
{
  static const Eigen::Vector3d palette[] = {
      {0.84, 0.15, 0.16}, {0.12, 0.47, 0.71}, {0.17, 0.63, 0.17}, {0.58, 0.40, 0.74},
      {1.00, 0.50, 0.05}, {0.55, 0.34, 0.29}, {0.89, 0.47, 0.76}, {0.09, 0.75, 0.81}};
  return palette[i % (sizeof(palette) / sizeof(palette[0]))];
}

/// One view: the bones, the ligaments and the landmarks in `viewport` of `window`.
void add_view(vtkRenderWindow* window, const AnatomyPicture& picture, const double viewport[4],
              const PictureCamera& camera, const std::string& caption)
{
  const vtkSmartPointer<vtkRenderer> renderer = add_white_renderer(window);
  renderer->SetViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
  for (vtkPolyData* bone : picture.bones)
    add_bone(renderer, bone, 0.3);
  for (vtkPolyData* ligament : picture.ligaments) {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(ligament);
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->SetColor(0.55, 0.55, 0.60);
    actor->GetProperty()->SetOpacity(0.6);
    renderer->AddActor(actor);
  }
  const int font = std::max(10, picture.height / 45);
  const Eigen::Vector3d view = camera.view_direction.normalized();
  for (std::size_t i = 0; i < picture.landmarks_mm.size(); ++i) {
    const Eigen::Vector3d& p = picture.landmarks_mm[i];
    vtkNew<vtkSphereSource> ball;
    ball->SetCenter(p.x(), p.y(), p.z());
    ball->SetRadius(0.012 * camera.view_height_mm);
    ball->SetThetaResolution(16);
    ball->SetPhiResolution(16);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(ball->GetOutputPort());
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    const Eigen::Vector3d c = colour_of(i);
    actor->GetProperty()->SetColor(c.x(), c.y(), c.z());
    renderer->AddActor(actor);
    // The name beside the ball, brought towards the camera so that the bones do not hide it.
    const Eigen::Vector3d at = p - camera.view_height_mm * view;
    vtkNew<vtkBillboardTextActor3D> name;
    name->SetInput(("  " + picture.landmark_names[i]).c_str());
    name->SetPosition(at.x(), at.y(), at.z());
    name->GetTextProperty()->SetFontSize(font);
    name->GetTextProperty()->SetColor(c.x(), c.y(), c.z());
    name->GetTextProperty()->SetBackgroundColor(1.0, 1.0, 1.0);
    name->GetTextProperty()->SetBackgroundOpacity(0.6);
    name->SetForceOpaque(true);
    renderer->AddActor(name);
  }
  add_caption(renderer, caption, picture.height);
  place_parallel_camera(renderer, camera);
}

} // namespace

void render_anatomy_png(const AnatomyPicture& picture, const std::filesystem::path& png)
{
  if (picture.bones.empty() && picture.landmarks_mm.empty())
    fail("nothing to draw in '{}': no bone and no landmark", png.string());
  if (picture.landmark_names.size() != picture.landmarks_mm.size())
    fail("the anatomy picture '{}' has {} names for {} landmarks", png.string(),
         picture.landmark_names.size(), picture.landmarks_mm.size());
  for (const Eigen::Vector3d* d : {&picture.proximal, &picture.posterior, &picture.medial})
    if (!d->allFinite() || std::abs(d->norm() - 1.0) > 1e-6)
      fail("the anatomy picture's directions must be unit vectors");
  if (std::abs(picture.proximal.dot(picture.posterior)) > 0.1)
    fail("the anatomy picture's proximal and posterior directions must lie across each other");

  // What the views show: the landmarks and 60 mm about them (or the bones' middle).
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : picture.landmarks_mm)
    centre += p / static_cast<double>(picture.landmarks_mm.size());
  double extent = 80.0;
  for (const Eigen::Vector3d& p : picture.landmarks_mm)
    extent = std::max(extent, 2.8 * (p - centre).norm());

  vtkNew<vtkRenderWindow> window;
  prepare_offscreen_window(window, picture.width, picture.height);
  const double front[4] = {0.0, 0.0, 0.5, 1.0}, side[4] = {0.5, 0.0, 1.0, 1.0};
  const std::string views = "front | medial side";
  add_view(window, picture, front, {centre, picture.posterior, picture.proximal, extent},
           picture.caption.empty() ? views : picture.caption + ", " + views);
  add_view(window, picture, side, {centre, -picture.medial, picture.proximal, extent}, "");
  write_window_png(window, png);
}

} // namespace ligsim::render
