#include "sim/scene/scene_output.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/pvd_file.hpp"
#include "common/vtk_files.hpp"

#include <fmt/format.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>

#include <cmath>
#include <vector>

namespace ligsim::sim {

namespace {

vtkSmartPointer<vtkDoubleArray> make_array(const char* name, int components, vtkIdType tuples)
{
  auto array = vtkSmartPointer<vtkDoubleArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(tuples);
  return array;
}

/// The body deformed to positions `x` (mm): point data "displacement"; cell data
/// "strain_energy_density" (MPa), "J", and with fibers "fiber_stretch" (|F a|) and
/// "fiber_direction" (unit, deformed). Throws SolverError naming the first non-finite position
/// or inverted element (`label` names the state in the message).
vtkSmartPointer<vtkUnstructuredGrid>
deformed_grid(const HyperelasticBody& body, const Eigen::VectorXd& x, const std::string& label)
{
  if (!x.allFinite())
    fail<SolverError>("{}: the positions are not finite; nothing written", label);
  const TetMesh& mesh = body.mesh();
  const vtkIdType node_count = mesh.V.rows();
  const vtkIdType element_count = body.element_count();

  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(node_count);
  auto displacement = make_array("displacement", 3, node_count);
  for (vtkIdType n = 0; n < node_count; ++n) {
    points->SetPoint(n, x(3 * n), x(3 * n + 1), x(3 * n + 2));
    for (int a = 0; a < 3; ++a)
      displacement->SetComponent(n, a, x(3 * n + a) - mesh.V(n, a));
  }
  grid->SetPoints(points);
  grid->GetPointData()->AddArray(displacement);

  // Linear tets, or 10-node ones in VTK_QUADRATIC_TETRA's order (the body's).
  const ElementNodes& elements = body.elements();
  const int nodes = body.nodes_per_element();
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  cells->AllocateExact(element_count, nodes * element_count);
  std::vector<vtkIdType> ids(static_cast<std::size_t>(nodes));
  for (vtkIdType e = 0; e < element_count; ++e) {
    for (int k = 0; k < nodes; ++k)
      ids[static_cast<std::size_t>(k)] = elements(e, k);
    cells->InsertNextCell(nodes, ids.data());
  }
  grid->SetCells(body.quadratic() ? VTK_QUADRATIC_TETRA : VTK_TETRA, cells);

  auto energy = make_array("strain_energy_density", 1, element_count);
  auto jacobian = make_array("J", 1, element_count);
  const bool fibers = body.material().has_fibers();
  vtkSmartPointer<vtkDoubleArray> stretch;
  vtkSmartPointer<vtkDoubleArray> direction;
  if (fibers) {
    stretch = make_array("fiber_stretch", 1, element_count);
    direction = make_array("fiber_direction", 3, element_count);
  }
  for (vtkIdType e = 0; e < element_count; ++e) {
    const ElementMeasures measures = body.measures(x, e);
    if (!std::isfinite(measures.energy_density_mpa) || !(measures.J > 0.0))
      fail<SolverError>("{}: element {} is inverted or has a non-finite energy (J = {:.3g}); "
                        "nothing written",
                        label, e, measures.J);
    energy->SetValue(e, measures.energy_density_mpa);
    jacobian->SetValue(e, measures.J);
    if (fibers) {
      stretch->SetValue(e, measures.fiber_stretch);
      const Eigen::Vector3d unit = measures.deformed_fiber.normalized();
      for (int a = 0; a < 3; ++a)
        direction->SetComponent(e, a, unit(a));
    }
  }
  grid->GetCellData()->AddArray(energy);
  grid->GetCellData()->AddArray(jacobian);
  if (fibers) {
    grid->GetCellData()->AddArray(stretch);
    grid->GetCellData()->AddArray(direction);
  }
  return grid;
}

} // namespace

SceneOutput::SceneOutput(const HyperelasticBody& body, std::filesystem::path directory)
    : m_body(body)
    , m_directory(std::move(directory))
{
  ensure_directory(m_directory);
}

void SceneOutput::write_step(int index, double time, const Eigen::VectorXd& x,
                             const PointArrays& extra)
{
  write(fmt::format("step_{:04d}.vtu", index), time, x, extra);
}

std::filesystem::path SceneOutput::write(const std::string& name, double time,
                                         const Eigen::VectorXd& x, const PointArrays& extra)
{
  auto grid = deformed_grid(m_body, x, name);
  for (const auto& [array_name, values] : extra) {
    if (values.size() != m_body.node_count() || !values.allFinite())
      fail<SolverError>("{}: point data \"{}\" is missing or not finite; nothing written", name,
                        array_name);
    auto array = make_array(array_name.c_str(), 1, m_body.node_count());
    for (int n = 0; n < m_body.node_count(); ++n)
      array->SetValue(n, values(n));
    grid->GetPointData()->AddArray(array);
  }
  write_vtk(grid, m_directory / name);
  m_steps.emplace_back(time, name);
  return m_directory / name;
}

void SceneOutput::finish(const std::string& pvd)
{
  if (!m_steps.empty())
    write_pvd(m_directory / pvd, m_steps);
}

} // namespace ligsim::sim
