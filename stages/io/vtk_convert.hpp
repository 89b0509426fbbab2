#pragma once
/// @brief Conversions between the stages' in-memory data and VTK data sets.

#include "common/mesh.hpp"

#include <vtkSmartPointer.h>

#include <Eigen/Core>

#include <string>
#include <vector>

class vtkDataSetAttributes;
class vtkPolyData;
class vtkUnstructuredGrid;

namespace ligsim::io {

vtkSmartPointer<vtkPolyData> to_polydata(const TriangleSurface& surface);
/// Triangles only; other cells are ignored. Throws InputError on a non-triangle polygon.
TriangleSurface from_polydata(vtkPolyData* polydata);

/// A polyline (one line cell through all points, in order).
vtkSmartPointer<vtkPolyData> polyline_to_polydata(const Points& points);
Points points_of(vtkPolyData* polydata);

vtkSmartPointer<vtkUnstructuredGrid> to_unstructured_grid(const TetMesh& mesh);
vtkSmartPointer<vtkUnstructuredGrid> to_unstructured_grid(const QuadraticTetMesh& mesh);
/// Linear tetrahedra; or, given `tet10`, 10-node ones too: then the result's T holds their
/// corners and `tet10` all their nodes (left empty for linear ones). Throws InputError if another
/// cell type is present, the two kinds are mixed, or quadratic ones come without `tet10`.
TetMesh from_unstructured_grid(vtkUnstructuredGrid* grid, QuadraticTetrahedra* tet10 = nullptr);

/// Adds a #rows x columns double array (vectors, scalars) to point or cell data.
void add_array(vtkDataSetAttributes* attributes, const std::string& name,
               const Eigen::Ref<const Eigen::MatrixXd>& values);
/// Adds a 0/1 unsigned char array.
void add_flags(vtkDataSetAttributes* attributes, const std::string& name,
               const std::vector<bool>& flags);
/// Reads an array back as a #tuples x components matrix; throws InputError naming it if absent.
Eigen::MatrixXd get_array(vtkDataSetAttributes* attributes, const std::string& name);

} // namespace ligsim::io
