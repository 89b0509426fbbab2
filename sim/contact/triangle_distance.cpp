#include "sim/contact/triangle_distance.hpp"

#include <vtkCellArray.h>
#include <vtkImplicitPolyDataDistance.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <cmath>

namespace ligsim::sim {

struct TriangleDistance::Locator {
  vtkSmartPointer<vtkImplicitPolyDataDistance> distance;
};

TriangleDistance::TriangleDistance(const TriangleSurface& surface)
    : m_locator(std::make_unique<Locator>())
{
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(surface.V.rows());
  for (Eigen::Index v = 0; v < surface.V.rows(); ++v)
    points->SetPoint(v, surface.V(v, 0), surface.V(v, 1), surface.V(v, 2));
  auto triangles = vtkSmartPointer<vtkCellArray>::New();
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f) {
    const vtkIdType corners[3] = {surface.F(f, 0), surface.F(f, 1), surface.F(f, 2)};
    triangles->InsertNextCell(3, corners);
  }
  auto polydata = vtkSmartPointer<vtkPolyData>::New();
  polydata->SetPoints(points);
  polydata->SetPolys(triangles);
  m_locator->distance = vtkSmartPointer<vtkImplicitPolyDataDistance>::New();
  m_locator->distance->SetInput(polydata);
}

TriangleDistance::~TriangleDistance() = default;

double TriangleDistance::operator()(const Eigen::Vector3d& p) const
{
  double xyz[3] = {p.x(), p.y(), p.z()};
  return std::abs(m_locator->distance->EvaluateFunction(xyz));
}

} // namespace ligsim::sim
