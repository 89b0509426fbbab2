#include "pipeline/render/knee_picture.hpp"

#include "common/error.hpp"
#include "pipeline/render/picture_parts.hpp"
#include "pipeline/render/window_png.hpp"

#include <Eigen/Geometry>
#include <vtkActor.h>
#include <vtkBillboardTextActor3D.h>
#include <vtkCellData.h>
#include <vtkColorTransferFunction.h>
#include <vtkDataArray.h>
#include <vtkDataSetSurfaceFilter.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkProperty2D.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <cmath>

namespace ligsim::render {

namespace {

constexpr const char* kStretchArray = "fiber_stretch";
constexpr const char* kStrainArray = "fiber_strain";

vtkDataArray* stretch_of(vtkUnstructuredGrid* grid)
{
  if (!grid || grid->GetNumberOfCells() == 0 || !grid->GetPoints())
    fail("no ligament to draw: a mesh is empty");
  vtkDataArray* array = grid->GetCellData()->GetArray(kStretchArray);
  if (!array || array->GetNumberOfComponents() != 1 ||
      array->GetNumberOfTuples() != grid->GetNumberOfCells())
    fail("the ligament to draw needs cell data '{}' with one value per cell", kStretchArray);
  return array;
}

/// A copy of `grid` sharing its points and cells, with cell data "fiber_strain" alone.
vtkSmartPointer<vtkUnstructuredGrid> with_strain(vtkUnstructuredGrid* grid)
{
  vtkDataArray* stretch = stretch_of(grid);
  auto copy = vtkSmartPointer<vtkUnstructuredGrid>::New();
  copy->ShallowCopy(grid);
  copy->GetCellData()->Initialize();
  vtkNew<vtkDoubleArray> strain;
  strain->SetName(kStrainArray);
  strain->SetNumberOfTuples(stretch->GetNumberOfTuples());
  for (vtkIdType c = 0; c < stretch->GetNumberOfTuples(); ++c)
    strain->SetValue(c, stretch->GetTuple1(c) - 1.0);
  copy->GetCellData()->AddArray(strain);
  return copy;
}

/// Blue (slack) through white (zero) to red (the top of the scale).
vtkSmartPointer<vtkColorTransferFunction> strain_colours(double low, double high)
{
  auto colours = vtkSmartPointer<vtkColorTransferFunction>::New();
  colours->SetColorSpaceToDiverging();
  if (low < 0.0)
    colours->AddRGBPoint(low, 0.23, 0.30, 0.75);
  colours->AddRGBPoint(0.0, 0.87, 0.87, 0.87);
  colours->AddRGBPoint(high, 0.71, 0.02, 0.15);
  colours->ClampingOn();
  return colours;
}

} // namespace

double fiber_strain_percentile(const std::vector<vtkUnstructuredGrid*>& ligaments, double fraction)
{
  if (!(fraction >= 0.0 && fraction <= 1.0))
    fail("a percentile needs a fraction in [0, 1], got {}", fraction);
  std::vector<double> values;
  for (vtkUnstructuredGrid* grid : ligaments) {
    vtkDataArray* stretch = stretch_of(grid);
    for (vtkIdType c = 0; c < stretch->GetNumberOfTuples(); ++c)
      if (std::isfinite(stretch->GetTuple1(c)))
        values.push_back(stretch->GetTuple1(c) - 1.0);
  }
  if (values.empty())
    fail("the ligaments' fiber stretch has no finite value");
  const auto nth =
      values.begin() +
      static_cast<std::ptrdiff_t>(std::lround(fraction * static_cast<double>(values.size() - 1)));
  std::nth_element(values.begin(), nth, values.end());
  return *nth;
}

void render_knee_png(const KneePicture& picture, const PictureCamera& camera,
                     const std::filesystem::path& png)
{
  if (picture.ligaments.empty())
    fail("no ligament to draw in '{}'", png.string());
  if (picture.names.size() != picture.ligaments.size())
    fail("the knee picture '{}' has {} names for {} ligaments", png.string(), picture.names.size(),
         picture.ligaments.size());
  if (!(picture.strain_min <= 0.0) || !(picture.strain_max > 0.0) ||
      !std::isfinite(picture.strain_min) || !std::isfinite(picture.strain_max))
    fail("the knee picture's strain scale must run from at most 0 to above 0, got {} to {}",
         picture.strain_min, picture.strain_max);
  if (!(picture.bone_opacity > 0.0 && picture.bone_opacity <= 1.0))
    fail("bone opacity must be in (0, 1], got {}", picture.bone_opacity);
  check_camera(camera);

  vtkNew<vtkRenderWindow> window;
  prepare_offscreen_window(window, picture.width, picture.height);
  const vtkSmartPointer<vtkRenderer> renderer = add_white_renderer(window);

  const auto colours = strain_colours(picture.strain_min, picture.strain_max);
  const int font = std::max(10, picture.height / 40);
  for (std::size_t l = 0; l < picture.ligaments.size(); ++l) {
    const auto grid = with_strain(picture.ligaments[l]);
    vtkNew<vtkDataSetSurfaceFilter> surface;
    surface->SetInputData(grid);
    vtkNew<vtkPolyDataNormals> normals;
    normals->SetInputConnection(surface->GetOutputPort());
    normals->ComputeCellNormalsOff();
    normals->SplittingOn();
    normals->SetFeatureAngle(60.0);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(normals->GetOutputPort());
    mapper->SetScalarModeToUseCellFieldData();
    mapper->SelectColorArray(kStrainArray);
    mapper->SetColorModeToMapScalars();
    mapper->SetLookupTable(colours);
    mapper->UseLookupTableScalarRangeOn();
    mapper->ScalarVisibilityOn();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->SetAmbient(0.45);
    actor->GetProperty()->SetDiffuse(0.55);
    renderer->AddActor(actor);

    // The name above the ligament on the screen, brought towards the camera so that nothing
    // hides it (the projection is parallel: that does not move it on the screen).
    const Eigen::Vector3d up = camera.up.normalized();
    const Eigen::Vector3d view = camera.view_direction.normalized();
    double top = -INFINITY;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (vtkIdType p = 0; p < grid->GetNumberOfPoints(); ++p) {
      Eigen::Vector3d x;
      grid->GetPoints()->GetPoint(p, x.data());
      top = std::max(top, x.dot(up));
      centre += x / static_cast<double>(grid->GetNumberOfPoints());
    }
    const Eigen::Vector3d at = centre + (top - centre.dot(up) + 0.03 * camera.view_height_mm) * up -
                               camera.view_height_mm * view;
    vtkNew<vtkBillboardTextActor3D> name;
    name->SetInput(picture.names[l].c_str());
    name->SetPosition(at.x(), at.y(), at.z());
    name->GetTextProperty()->SetFontSize(font);
    name->GetTextProperty()->SetColor(0.0, 0.0, 0.0);
    name->GetTextProperty()->SetBackgroundColor(1.0, 1.0, 1.0);
    name->GetTextProperty()->SetBackgroundOpacity(0.7);
    name->GetTextProperty()->SetJustificationToCentered();
    name->SetForceOpaque(true);
    renderer->AddActor(name);
  }

  for (std::size_t i = 0; i < picture.bones.size(); ++i) {
    if (!picture.bones[i])
      fail("bone surface {} to draw in '{}' is missing", i, png.string());
    add_bone(renderer, picture.bones[i], picture.bone_opacity);
  }
  add_scale_bar(renderer, colours, "fiber strain\n(stretch - 1)", font, 0.82, 0.16);
  add_caption(renderer, picture.caption, picture.height);

  place_parallel_camera(renderer, camera);
  write_window_png(window, png);
}

} // namespace ligsim::render
