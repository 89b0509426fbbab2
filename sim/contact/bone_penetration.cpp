#include "sim/contact/bone_penetration.hpp"

#include <vtkCellArray.h>
#include <vtkImplicitPolyDataDistance.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <cmath>

namespace ligsim::sim {

BonePenetration::BonePenetration(const TriangleSurface& bone)
    : m_winding(bone)
    , m_distance(vtkSmartPointer<vtkImplicitPolyDataDistance>::New())
{
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(bone.V.rows());
  for (Eigen::Index v = 0; v < bone.V.rows(); ++v)
    points->SetPoint(v, bone.V(v, 0), bone.V(v, 1), bone.V(v, 2));
  auto triangles = vtkSmartPointer<vtkCellArray>::New();
  for (Eigen::Index f = 0; f < bone.F.rows(); ++f) {
    const vtkIdType corners[3] = {bone.F(f, 0), bone.F(f, 1), bone.F(f, 2)};
    triangles->InsertNextCell(3, corners);
  }
  auto polydata = vtkSmartPointer<vtkPolyData>::New();
  polydata->SetPoints(points);
  polydata->SetPolys(triangles);
  m_distance->SetInput(polydata);
}

BonePenetration::~BonePenetration() = default;

double BonePenetration::depth_mm(const Eigen::Vector3d& p) const
{
  if (!m_winding.bounds().contains(p) || std::abs(m_winding(p)) < 0.5)
    return 0.0;
  double xyz[3] = {p.x(), p.y(), p.z()};
  return std::abs(m_distance->EvaluateFunction(xyz));
}

} // namespace ligsim::sim
