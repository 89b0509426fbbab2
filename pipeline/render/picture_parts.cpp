#include "pipeline/render/picture_parts.hpp"

#include "common/error.hpp"

#include <Eigen/Geometry>

#include <vtkActor.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkProperty2D.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkScalarsToColors.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>

#include <algorithm>
#include <cmath>

namespace ligsim::render {

void check_camera(const PictureCamera& camera)
{
  const double along = camera.view_direction.norm();
  if (!camera.focal_point_mm.allFinite() || !camera.view_direction.allFinite() ||
      !camera.up.allFinite() || !(along > 0.0))
    fail("the picture's camera needs a finite focal point and a non-zero view direction");
  if (!(camera.up.cross(camera.view_direction / along).norm() > 1e-6 * camera.up.norm()))
    fail("the picture's up direction [{}, {}, {}] is zero or along the view direction",
         camera.up.x(), camera.up.y(), camera.up.z());
  if (!(camera.view_height_mm > 0.0) || !std::isfinite(camera.view_height_mm))
    fail("the picture's view height must be positive, got {} mm", camera.view_height_mm);
}

vtkSmartPointer<vtkRenderer> add_white_renderer(vtkRenderWindow* window)
{
  auto renderer = vtkSmartPointer<vtkRenderer>::New();
  renderer->SetBackground(1.0, 1.0, 1.0);
  renderer->UseFXAAOn();
  window->AddRenderer(renderer);
  return renderer;
}

vtkSmartPointer<vtkActor> add_bone(vtkRenderer* renderer, vtkPolyData* bone, double opacity)
{
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputData(bone);
  normals->SetFeatureAngle(60.0);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(normals->GetOutputPort());
  mapper->ScalarVisibilityOff();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(kBoneColour.x(), kBoneColour.y(), kBoneColour.z());
  actor->GetProperty()->SetOpacity(opacity);
  actor->GetProperty()->SetAmbient(0.3);
  actor->GetProperty()->SetDiffuse(0.7);
  renderer->AddActor(actor);
  return actor;
}

vtkSmartPointer<vtkScalarBarActor> add_scale_bar(vtkRenderer* renderer, vtkScalarsToColors* colours,
                                                 const char* title, int font, double left,
                                                 double width)
{
  auto scale = vtkSmartPointer<vtkScalarBarActor>::New();
  scale->SetLookupTable(colours);
  scale->SetTitle(title);
  scale->SetNumberOfLabels(5);
  scale->SetLabelFormat("%.3g");
  scale->SetPosition(left, 0.06);
  scale->SetWidth(width);
  scale->SetHeight(0.84);
  scale->SetBarRatio(0.25);
  scale->SetVerticalTitleSeparation(font / 2);
  scale->UnconstrainedFontSizeOn();
  scale->DrawBackgroundOn(); // legible where the bar overlaps the scene
  scale->GetBackgroundProperty()->SetColor(1.0, 1.0, 1.0);
  scale->GetBackgroundProperty()->SetOpacity(0.85);
  for (vtkTextProperty* text : {scale->GetTitleTextProperty(), scale->GetLabelTextProperty()}) {
    text->SetColor(0.0, 0.0, 0.0);
    text->SetFontSize(font);
    text->BoldOff();
    text->ItalicOff();
    text->ShadowOff();
  }
  renderer->AddViewProp(scale);
  return scale;
}

void add_caption(vtkRenderer* renderer, const std::string& caption, int height)
{
  if (caption.empty())
    return;
  vtkNew<vtkTextActor> text;
  text->SetInput(caption.c_str());
  text->GetTextProperty()->SetColor(0.0, 0.0, 0.0);
  text->GetTextProperty()->SetFontSize(std::max(12, height / 28));
  text->GetTextProperty()->SetVerticalJustificationToTop();
  text->SetDisplayPosition(height / 60, height - height / 60);
  renderer->AddViewProp(text);
}

} // namespace ligsim::render
