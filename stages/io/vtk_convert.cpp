#include "stages/io/vtk_convert.hpp"

#include "common/error.hpp"

#include <vtkCellArray.h>
#include <vtkCellType.h>
#include <vtkDataArray.h>
#include <vtkDataSetAttributes.h>
#include <vtkDoubleArray.h>
#include <vtkIdList.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>

#include <cmath>

namespace ligsim::io {

namespace {

vtkSmartPointer<vtkPoints> to_vtk_points(const Points& V)
{
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(V.rows());
  for (Eigen::Index i = 0; i < V.rows(); ++i)
    points->SetPoint(i, V(i, 0), V(i, 1), V(i, 2));
  return points;
}

Points from_vtk_points(vtkPoints* points)
{
  Points V(points ? points->GetNumberOfPoints() : 0, 3);
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    double p[3];
    points->GetPoint(i, p);
    V.row(i) << p[0], p[1], p[2];
  }
  return V;
}

} // namespace

vtkSmartPointer<vtkPolyData> to_polydata(const TriangleSurface& surface)
{
  auto polys = vtkSmartPointer<vtkCellArray>::New();
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f) {
    const vtkIdType ids[3] = {surface.F(f, 0), surface.F(f, 1), surface.F(f, 2)};
    polys->InsertNextCell(3, ids);
  }
  auto polydata = vtkSmartPointer<vtkPolyData>::New();
  polydata->SetPoints(to_vtk_points(surface.V));
  polydata->SetPolys(polys);
  return polydata;
}

TriangleSurface from_polydata(vtkPolyData* polydata)
{
  TriangleSurface surface;
  surface.V = from_vtk_points(polydata->GetPoints());
  vtkCellArray* polys = polydata->GetPolys();
  surface.F.resize(polys ? polys->GetNumberOfCells() : 0, 3);
  if (!polys)
    return surface;
  auto ids = vtkSmartPointer<vtkIdList>::New();
  Eigen::Index f = 0;
  for (polys->InitTraversal(); polys->GetNextCell(ids);) {
    if (ids->GetNumberOfIds() != 3)
      fail("polygon {} has {} vertices, expected a triangle", f, ids->GetNumberOfIds());
    surface.F.row(f++) << static_cast<int>(ids->GetId(0)), static_cast<int>(ids->GetId(1)),
        static_cast<int>(ids->GetId(2));
  }
  return surface;
}

vtkSmartPointer<vtkPolyData> polyline_to_polydata(const Points& points)
{
  auto line = vtkSmartPointer<vtkCellArray>::New();
  line->InsertNextCell(static_cast<int>(points.rows()));
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    line->InsertCellPoint(i);
  auto polydata = vtkSmartPointer<vtkPolyData>::New();
  polydata->SetPoints(to_vtk_points(points));
  polydata->SetLines(line);
  return polydata;
}

Points points_of(vtkPolyData* polydata)
{
  return from_vtk_points(polydata->GetPoints());
}

vtkSmartPointer<vtkUnstructuredGrid> to_unstructured_grid(const TetMesh& mesh)
{
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->SetPoints(to_vtk_points(mesh.V));
  grid->Allocate(mesh.T.rows());
  for (Eigen::Index t = 0; t < mesh.T.rows(); ++t) {
    const vtkIdType ids[4] = {mesh.T(t, 0), mesh.T(t, 1), mesh.T(t, 2), mesh.T(t, 3)};
    grid->InsertNextCell(VTK_TETRA, 4, ids);
  }
  return grid;
}

vtkSmartPointer<vtkUnstructuredGrid> to_unstructured_grid(const QuadraticTetMesh& mesh)
{
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->SetPoints(to_vtk_points(mesh.V));
  grid->Allocate(mesh.T.rows());
  for (Eigen::Index t = 0; t < mesh.T.rows(); ++t) {
    vtkIdType ids[10];
    for (int k = 0; k < 10; ++k)
      ids[k] = mesh.T(t, k);
    grid->InsertNextCell(VTK_QUADRATIC_TETRA, 10, ids);
  }
  return grid;
}

TetMesh from_unstructured_grid(vtkUnstructuredGrid* grid, QuadraticTetrahedra* tet10)
{
  TetMesh mesh;
  mesh.V = from_vtk_points(grid->GetPoints());
  const vtkIdType cells = grid->GetNumberOfCells();
  mesh.T.resize(cells, 4);
  const bool quadratic = cells > 0 && grid->GetCellType(0) == VTK_QUADRATIC_TETRA;
  if (quadratic && !tet10)
    fail("the mesh has 10-node (quadratic) tetrahedra where linear ones are expected");
  if (quadratic)
    tet10->resize(cells, 10);
  const int expected = quadratic ? VTK_QUADRATIC_TETRA : VTK_TETRA;
  auto ids = vtkSmartPointer<vtkIdList>::New();
  for (vtkIdType c = 0; c < cells; ++c) {
    if (grid->GetCellType(c) != expected)
      fail("cell {} is not a {} tetrahedron like cell 0 (VTK type {}): a mesh is of linear "
           "(VTK_TETRA) or of quadratic (VTK_QUADRATIC_TETRA) tets",
           c, quadratic ? "quadratic" : "linear", grid->GetCellType(c));
    grid->GetCellPoints(c, ids);
    for (int k = 0; k < (quadratic ? 10 : 4); ++k) {
      const auto id = static_cast<int>(ids->GetId(k));
      if (k < 4)
        mesh.T(c, k) = id;
      if (quadratic)
        (*tet10)(c, k) = id;
    }
  }
  return mesh;
}

void add_array(vtkDataSetAttributes* attributes, const std::string& name,
               const Eigen::Ref<const Eigen::MatrixXd>& values)
{
  auto array = vtkSmartPointer<vtkDoubleArray>::New();
  array->SetName(name.c_str());
  array->SetNumberOfComponents(static_cast<int>(values.cols()));
  array->SetNumberOfTuples(values.rows());
  for (Eigen::Index i = 0; i < values.rows(); ++i)
    for (Eigen::Index c = 0; c < values.cols(); ++c)
      array->SetComponent(i, static_cast<int>(c), values(i, c));
  attributes->AddArray(array);
}

void add_flags(vtkDataSetAttributes* attributes, const std::string& name,
               const std::vector<bool>& flags)
{
  auto array = vtkSmartPointer<vtkUnsignedCharArray>::New();
  array->SetName(name.c_str());
  array->SetNumberOfValues(static_cast<vtkIdType>(flags.size()));
  for (std::size_t i = 0; i < flags.size(); ++i)
    array->SetValue(static_cast<vtkIdType>(i), flags[i] ? 1 : 0);
  attributes->AddArray(array);
}

Eigen::MatrixXd get_array(vtkDataSetAttributes* attributes, const std::string& name)
{
  vtkDataArray* array = attributes->GetArray(name.c_str());
  if (array == nullptr)
    fail("missing data array '{}'", name);
  Eigen::MatrixXd values(array->GetNumberOfTuples(), array->GetNumberOfComponents());
  for (Eigen::Index i = 0; i < values.rows(); ++i)
    for (Eigen::Index c = 0; c < values.cols(); ++c)
      values(i, c) = array->GetComponent(i, static_cast<int>(c));
  return values;
}

} // namespace ligsim::io
