#include "pipeline/render/membrane_frame.hpp"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkIdTypeArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>

#include <cmath>

namespace ligsim::render {

using membrane::Triangle;
using membrane::Vec2;

vtkSmartPointer<vtkUnstructuredGrid> membrane_frame(const membrane::TearSimulation& simulation,
                                                    const std::vector<double>& criterion)
{
  const membrane::MembraneMesh& mesh = simulation.mesh();
  const membrane::CorotationalElements& elements = simulation.elements();
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();

  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(mesh.node_count());
  auto displacement = vtkSmartPointer<vtkDoubleArray>::New();
  displacement->SetName("displacement");
  displacement->SetNumberOfComponents(3);
  displacement->SetNumberOfTuples(mesh.node_count());
  for (int v = 0; v < mesh.node_count(); ++v) {
    points->SetPoint(v, mesh.position[v].x(), mesh.position[v].y(), 0.0);
    const Vec2 u = mesh.position[v] - mesh.rest[v];
    displacement->SetTuple3(v, u.x(), u.y(), 0.0);
  }
  grid->SetPoints(points);
  grid->GetPointData()->AddArray(displacement);

  const auto cracks = crack_edges(mesh);
  const vtkIdType cells = mesh.triangle_count() + static_cast<vtkIdType>(cracks.size());
  grid->Allocate(cells);
  for (const Triangle& t : mesh.triangles) {
    const vtkIdType ids[3] = {t[0], t[1], t[2]};
    grid->InsertNextCell(VTK_TRIANGLE, 3, ids);
  }
  for (const auto& edge : cracks) {
    const vtkIdType ids[2] = {edge[0], edge[1]};
    grid->InsertNextCell(VTK_LINE, 2, ids);
  }

  const auto array = [&](const char* name, int components) {
    auto values = vtkSmartPointer<vtkDoubleArray>::New();
    values->SetName(name);
    values->SetNumberOfComponents(components);
    values->SetNumberOfTuples(cells);
    values->Fill(0.0);
    grid->GetCellData()->AddArray(values);
    return values;
  };
  auto shading = array("criterion", 1);
  auto fiber = array("fiber", 3);
  auto stress = array("stress", 3);
  auto crack = vtkSmartPointer<vtkUnsignedCharArray>::New();
  crack->SetName("crack");
  crack->SetNumberOfTuples(cells);
  crack->Fill(0);
  grid->GetCellData()->AddArray(crack);
  for (int tri = 0; tri < mesh.triangle_count(); ++tri) {
    shading->SetValue(tri, criterion[tri]);
    // The fiber turns with the element: R f.
    const double angle = mesh.fiber_angle_rad[tri] +
                         std::atan2(elements.rotation(tri).y(), elements.rotation(tri).x());
    fiber->SetTuple3(tri, std::cos(angle), std::sin(angle), 0.0);
    const Eigen::Vector3d& s = elements.stress(tri);
    stress->SetTuple3(tri, s[0], s[1], s[2]);
  }
  for (vtkIdType cell = mesh.triangle_count(); cell < cells; ++cell)
    crack->SetValue(cell, 1);
  return grid;
}

} // namespace ligsim::render
