#include "sim/scene/vtu_mesh.hpp"

#include "common/error.hpp"
#include "common/vtk_files.hpp"
#include "stages/io/vtk_convert.hpp"

#include <vtkCellData.h>
#include <vtkDataArray.h>
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
  try {
    result.mesh = io::from_unstructured_grid(grid, &result.tet10);
  } catch (const InputError& error) {
    fail("{}: {}", file.string(), error.what());
  }
  result.point_data = arrays_of(grid->GetPointData());
  result.cell_data = arrays_of(grid->GetCellData());
  return result;
}

} // namespace ligsim::sim
