#include "pipeline/render/ligament_picture.hpp"

#include "common/error.hpp"
#include "pipeline/render/picture_parts.hpp"
#include "pipeline/render/window_png.hpp"

#include <Eigen/Geometry>
#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDataSetSurfaceFilter.h>
#include <vtkIdList.h>
#include <vtkIdTypeArray.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPoints.h>
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
#include <cstdint>
#include <random>
#include <unordered_map>
#include <utility>

namespace ligsim::render {

namespace {

constexpr const char* kEnergyArray = "strain_energy_density";
constexpr const char* kFiberArray = "fiber_direction";
constexpr const char* kOriginalIds = "vtkOriginalCellIds";
/// Fiber strokes are at least this many stroke lengths apart, so that they stay readable.
constexpr double kStrokeSpacing = 1.25;

Eigen::Vector3d point(vtkPoints* points, vtkIdType id)
{
  Eigen::Vector3d p;
  points->GetPoint(id, p.data());
  return p;
}

vtkDataArray* cell_array(vtkUnstructuredGrid* grid, const char* name, int components)
{
  vtkDataArray* array = grid->GetCellData()->GetArray(name);
  if (!array || array->GetNumberOfComponents() != components ||
      array->GetNumberOfTuples() != grid->GetNumberOfCells())
    fail("the ligament to draw needs cell data '{}' with {} component(s) per cell", name,
         components);
  return array;
}

/// Mean distance between the points of a cell, over all cells: the mean edge for tets.
double mean_edge_length(vtkUnstructuredGrid* grid)
{
  vtkNew<vtkIdList> ids;
  double sum = 0.0;
  long count = 0;
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c) {
    grid->GetCellPoints(c, ids);
    const vtkIdType n = std::min<vtkIdType>(ids->GetNumberOfIds(), 8);
    for (vtkIdType a = 0; a < n; ++a)
      for (vtkIdType b = a + 1; b < n; ++b) {
        sum += (point(grid->GetPoints(), ids->GetId(a)) - point(grid->GetPoints(), ids->GetId(b)))
                   .norm();
        ++count;
      }
  }
  return count > 0 ? sum / count : 0.0;
}

/// 0 .. n-1 in a random order with a fixed seed, so that the same mesh gets the same strokes at
/// every angle.
std::vector<vtkIdType> shuffled(vtkIdType n)
{
  std::vector<vtkIdType> order(static_cast<size_t>(n));
  for (vtkIdType i = 0; i < n; ++i)
    order[static_cast<size_t>(i)] = i;
  std::mt19937 random(1);
  for (vtkIdType i = n - 1; i > 0; --i)
    std::swap(order[static_cast<size_t>(i)],
              order[static_cast<size_t>(random() % static_cast<uint32_t>(i + 1))]);
  return order;
}

/// Surface points kept at least `spacing` apart from those whose normal is within 60 degrees of
/// theirs (so the two sides of a thin sheet do not crowd each other out); a hash grid of cells
/// `spacing` wide.
class SpacedPoints {
public:
  explicit SpacedPoints(double spacing)
      : m_spacing(spacing)
  {
  }

  /// Keeps `p` (unit `normal`) and returns true if no kept point faces the same way closer
  /// than the spacing.
  bool try_add(const Eigen::Vector3d& p, const Eigen::Vector3d& normal)
  {
    const Eigen::Vector3i cell = (p / m_spacing).array().floor().cast<int>();
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const auto found = m_cells.find(key(cell + Eigen::Vector3i(dx, dy, dz)));
          if (found == m_cells.end())
            continue;
          for (const auto& [q, q_normal] : found->second)
            if ((q - p).squaredNorm() < m_spacing * m_spacing && q_normal.dot(normal) > 0.5)
              return false;
        }
    m_cells[key(cell)].emplace_back(p, normal);
    return true;
  }

private:
  static uint64_t key(const Eigen::Vector3i& cell)
  {
    auto part = [](int i) { return static_cast<uint64_t>(static_cast<uint32_t>(i) & 0x1fffffu); };
    return part(cell.x()) | part(cell.y()) << 21 | part(cell.z()) << 42;
  }

  double m_spacing;
  std::unordered_map<uint64_t, std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>>> m_cells;
};

/// Strokes on boundary faces taken in random order, each at least kStrokeSpacing stroke lengths
/// from the others, at most `max_fibers`: through the face's centre, lifted off the surface by a
/// twentieth of `length`, along the face's tet fiber projected onto the face, as long as the
/// projection of a fiber segment of `length`.
vtkSmartPointer<vtkPolyData> fiber_strokes(vtkUnstructuredGrid* grid, vtkPolyData* surface,
                                           double length, int max_fibers)
{
  vtkDataArray* fibers = grid->GetCellData()->GetArray(kFiberArray);
  auto* original = vtkIdTypeArray::SafeDownCast(surface->GetCellData()->GetArray(kOriginalIds));
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> lines;
  vtkNew<vtkIdList> face;
  vtkNew<vtkIdList> tet;
  SpacedPoints spaced(kStrokeSpacing * length);
  for (const vtkIdType f : shuffled(surface->GetNumberOfCells())) {
    if (lines->GetNumberOfCells() >= max_fibers)
      break;
    surface->GetCellPoints(f, face);
    if (face->GetNumberOfIds() < 3)
      continue;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (vtkIdType i = 0; i < face->GetNumberOfIds(); ++i)
      centre += point(surface->GetPoints(), face->GetId(i));
    centre /= static_cast<double>(face->GetNumberOfIds());
    const Eigen::Vector3d p0 = point(surface->GetPoints(), face->GetId(0));
    const Eigen::Vector3d p1 = point(surface->GetPoints(), face->GetId(1));
    const Eigen::Vector3d p2 = point(surface->GetPoints(), face->GetId(2));
    Eigen::Vector3d normal = (p1 - p0).cross(p2 - p0);
    if (!(normal.norm() > 0.0))
      continue;
    normal.normalize();

    const vtkIdType cell = original->GetValue(f);
    grid->GetCellPoints(cell, tet);
    Eigen::Vector3d inside = Eigen::Vector3d::Zero();
    for (vtkIdType i = 0; i < tet->GetNumberOfIds(); ++i)
      inside += point(grid->GetPoints(), tet->GetId(i));
    inside /= static_cast<double>(tet->GetNumberOfIds());
    if (normal.dot(centre - inside) < 0.0)
      normal = -normal;

    Eigen::Vector3d fiber;
    fibers->GetTuple(cell, fiber.data());
    const Eigen::Vector3d along = fiber - fiber.dot(normal) * normal;
    if (!(fiber.norm() > 0.0) || !along.allFinite() || along.norm() < 0.05 * fiber.norm())
      continue; // no fiber, or one seen end-on
    if (!spaced.try_add(centre, normal))
      continue;
    const Eigen::Vector3d mid = centre + 0.05 * length * normal;
    const Eigen::Vector3d half = 0.5 * length * along / std::max(fiber.norm(), 1e-12);
    const Eigen::Vector3d start = mid - half, end = mid + half;
    const vtkIdType a = points->InsertNextPoint(start.data());
    const vtkIdType b = points->InsertNextPoint(end.data());
    const vtkIdType segment[2] = {a, b};
    lines->InsertNextCell(2, segment);
  }
  vtkNew<vtkPolyData> strokes;
  strokes->SetPoints(points);
  strokes->SetLines(lines);
  return strokes;
}

/// Green (low) through yellow to red (high), as the paper's Figure 4.
vtkSmartPointer<vtkLookupTable> energy_colours(double max_mpa)
{
  vtkNew<vtkLookupTable> table;
  table->SetNumberOfTableValues(256);
  table->SetHueRange(1.0 / 3.0, 0.0);
  table->SetSaturationRange(1.0, 1.0);
  table->SetValueRange(0.9, 0.9);
  table->SetRange(0.0, max_mpa);
  table->Build();
  return table;
}

} // namespace

void place_parallel_camera(vtkRenderer* renderer, const PictureCamera& camera)
{
  double bounds[6];
  renderer->ComputeVisiblePropBounds(bounds);
  const Eigen::Vector3d low(bounds[0], bounds[2], bounds[4]);
  const Eigen::Vector3d high(bounds[1], bounds[3], bounds[5]);
  const Eigen::Vector3d direction = camera.view_direction.normalized();
  // Far enough back that the whole scene is in front of the camera.
  double distance = 1.0 + camera.view_height_mm;
  if ((high.array() >= low.array()).all())
    distance += (high - low).norm() + (0.5 * (low + high) - camera.focal_point_mm).norm();
  const Eigen::Vector3d position = camera.focal_point_mm - distance * direction;

  vtkCamera* view = renderer->GetActiveCamera();
  view->ParallelProjectionOn();
  view->SetFocalPoint(camera.focal_point_mm.data());
  view->SetPosition(position.data());
  view->SetViewUp(camera.up.data());
  view->OrthogonalizeViewUp();
  view->SetParallelScale(0.5 * camera.view_height_mm);
  renderer->ResetCameraClippingRange();
}

double strain_energy_percentile_mpa(vtkUnstructuredGrid* ligament, double fraction)
{
  if (!ligament || ligament->GetNumberOfCells() == 0)
    fail("no ligament to take a strain energy percentile of: the mesh is empty");
  if (!(fraction >= 0.0 && fraction <= 1.0))
    fail("a percentile needs a fraction in [0, 1], got {}", fraction);
  vtkDataArray* energy = cell_array(ligament, kEnergyArray, 1);
  std::vector<double> values;
  values.reserve(static_cast<size_t>(energy->GetNumberOfTuples()));
  for (vtkIdType c = 0; c < energy->GetNumberOfTuples(); ++c)
    if (std::isfinite(energy->GetTuple1(c)))
      values.push_back(energy->GetTuple1(c));
  if (values.empty())
    fail("the ligament's strain energy density has no finite value");
  const auto nth =
      values.begin() +
      static_cast<std::ptrdiff_t>(std::lround(fraction * static_cast<double>(values.size() - 1)));
  std::nth_element(values.begin(), nth, values.end());
  return *nth;
}

void render_ligament_png(const LigamentPicture& picture, const PictureCamera& camera,
                         const std::filesystem::path& png)
{
  vtkUnstructuredGrid* grid = picture.ligament;
  if (!grid || grid->GetNumberOfCells() == 0 || !grid->GetPoints())
    fail("no ligament to draw in '{}': the mesh is empty", png.string());
  vtkDataArray* energy = cell_array(grid, kEnergyArray, 1);
  cell_array(grid, kFiberArray, 3);
  check_camera(camera);
  if (!(picture.bone_opacity > 0.0 && picture.bone_opacity <= 1.0))
    fail("bone opacity must be in (0, 1], got {}", picture.bone_opacity);

  double energy_max = picture.energy_max_mpa;
  if (!(energy_max > 0.0) || !std::isfinite(energy_max))
    energy_max = energy->GetRange()[1];
  if (!(energy_max > 0.0) || !std::isfinite(energy_max))
    energy_max = 1.0; // an unloaded frame: all green

  vtkNew<vtkRenderWindow> window;
  prepare_offscreen_window(window, picture.width, picture.height);
  const vtkSmartPointer<vtkRenderer> renderer = add_white_renderer(window);

  // The ligament's outer surface, coloured per cell.
  vtkNew<vtkDataSetSurfaceFilter> surface;
  surface->SetInputData(grid);
  surface->PassThroughCellIdsOn();
  surface->SetOriginalCellIdsName(kOriginalIds);
  surface->Update();
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputConnection(surface->GetOutputPort());
  normals->ComputeCellNormalsOff();
  normals->ConsistencyOn();
  normals->SplittingOn();
  normals->SetFeatureAngle(60.0);

  const vtkSmartPointer<vtkLookupTable> colours = energy_colours(energy_max);
  vtkNew<vtkPolyDataMapper> ligament_mapper;
  ligament_mapper->SetInputConnection(normals->GetOutputPort());
  ligament_mapper->SetScalarModeToUseCellFieldData();
  ligament_mapper->SelectColorArray(kEnergyArray);
  ligament_mapper->SetColorModeToMapScalars();
  ligament_mapper->SetLookupTable(colours);
  ligament_mapper->UseLookupTableScalarRangeOn();
  ligament_mapper->ScalarVisibilityOn();
  vtkNew<vtkActor> ligament;
  ligament->SetMapper(ligament_mapper);
  ligament->GetProperty()->SetAmbient(0.45); // colours stay close to the scale on oblique faces
  ligament->GetProperty()->SetDiffuse(0.55);
  renderer->AddActor(ligament);

  // Fiber strokes, dark and unlit, on top of the surface.
  const double stroke = mean_edge_length(grid);
  vtkNew<vtkPolyDataMapper> fiber_mapper;
  fiber_mapper->SetInputData(fiber_strokes(grid, surface->GetOutput(), stroke, picture.max_fibers));
  fiber_mapper->ScalarVisibilityOff();
  vtkNew<vtkActor> fibers;
  fibers->SetMapper(fiber_mapper);
  fibers->GetProperty()->SetColor(0.12, 0.12, 0.12);
  fibers->GetProperty()->SetLighting(false);
  fibers->GetProperty()->SetLineWidth(std::max(1.0f, static_cast<float>(picture.height) / 600.0f));
  renderer->AddActor(fibers);

  // Where the ligament touches a bone: blue dots over everything else of the ligament.
  if (!picture.contact_points_mm.empty()) {
    vtkNew<vtkPoints> points;
    vtkNew<vtkCellArray> vertices;
    for (const Eigen::Vector3d& p : picture.contact_points_mm) {
      const vtkIdType id = points->InsertNextPoint(p.data());
      vertices->InsertNextCell(1, &id);
    }
    vtkNew<vtkPolyData> dots;
    dots->SetPoints(points);
    dots->SetVerts(vertices);
    vtkNew<vtkPolyDataMapper> dot_mapper;
    dot_mapper->SetInputData(dots);
    dot_mapper->ScalarVisibilityOff();
    vtkNew<vtkActor> contact;
    contact->SetMapper(dot_mapper);
    contact->GetProperty()->SetColor(0.1, 0.3, 0.95);
    contact->GetProperty()->SetPointSize(
        std::max(3.0f, static_cast<float>(picture.height) / 150.0f));
    contact->GetProperty()->SetRenderPointsAsSpheres(true);
    renderer->AddActor(contact);
  }

  // Bones.
  std::vector<vtkSmartPointer<vtkActor>> bones;
  for (size_t i = 0; i < picture.bones.size(); ++i) {
    if (!picture.bones[i])
      fail("bone surface {} to draw in '{}' is missing", i, png.string());
    bones.push_back(add_bone(renderer, picture.bones[i], picture.bone_opacity));
  }

  // Colour scale and caption.
  const int font = std::max(10, picture.height / 40);
  const auto scale =
      add_scale_bar(renderer, colours, "strain energy density\n(MPa = mJ/mm^3)", font, 0.80, 0.18);
  scale->GetTitleTextProperty()->SetFontSize(font - font / 6);
  add_caption(renderer, picture.caption, picture.height);

  place_parallel_camera(renderer, camera);
  write_window_png(window, png);
}

} // namespace ligsim::render
