#include "sim/scene/vtu_mesh.hpp"

#include "common/error.hpp"
#include "common/vtk_files.hpp"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkPointData.h>
#include <vtkUnstructuredGrid.h>

namespace ligsim::sim {

namespace {

std::map<std::string, Eigen::MatrixXd> arrays_of(vtkFieldData* data)
{
  std::map<std::string, Eigen::MatrixXd> arrays;
  for (int a = 0; a < data->GetNumberOfArrays(); ++a) {
    vtkDataArray* array = data->GetArray(a);
    if (!array || !array->GetName())
      continue;
    Eigen::MatrixXd values(array->GetNumberOfTuples(), array->GetNumberOfComponents());
    for (vtkIdType t = 0; t < array->GetNumberOfTuples(); ++t)
      for (int c = 0; c < array->GetNumberOfComponents(); ++c)
        values(t, c) = array->GetComponent(t, c);
    arrays[array->GetName()] = std::move(values);
  }
  return arrays;
}

} // namespace

VtuMesh read_vtu_mesh(const std::filesystem::path& file)
{
  vtkSmartPointer<vtkUnstructuredGrid> grid = read_vtu(file);
  VtuMesh result;
  const vtkIdType points = grid->GetNumberOfPoints();
  const vtkIdType cells = grid->GetNumberOfCells();
  if (points == 0 || cells == 0)
    fail("{}: the mesh has no points or no cells", file.string());
  result.mesh.V.resize(points, 3);
  for (vtkIdType p = 0; p < points; ++p) {
    double xyz[3];
    grid->GetPoint(p, xyz);
    result.mesh.V.row(p) << xyz[0], xyz[1], xyz[2];
  }
  result.mesh.T.resize(cells, 4);
  auto ids = vtkSmartPointer<vtkIdList>::New();
  for (vtkIdType c = 0; c < cells; ++c) {
    if (grid->GetCellType(c) != VTK_TETRA)
      fail("{}: cell {} is not a linear tetrahedron (VTK cell type {})", file.string(), c,
           grid->GetCellType(c));
    grid->GetCellPoints(c, ids);
    for (int i = 0; i < 4; ++i)
      result.mesh.T(c, i) = static_cast<int>(ids->GetId(i));
  }
  result.point_data = arrays_of(grid->GetPointData());
  result.cell_data = arrays_of(grid->GetCellData());
  return result;
}

} // namespace ligsim::sim
