#pragma once
/// @brief A frame of a tearing run as a VTK unstructured grid, for ParaView.
///
/// Points: current positions (z = 0), with point data "displacement" (mm). Cells: the
/// triangles, then the crack edges as lines (each crack face once). Cell data: "criterion"
/// (the largest c over all directions at the element, eq. 4 without the gate, for shading;
/// 0 on lines), "fiber" (unit fiber direction in the current frame), "stress" (sigma_x,
/// sigma_y, tau_xy in the element's rest frame, MPa), "crack" (1 on crack lines, else 0).

#include "sim/membrane/scene/tear_simulation.hpp"

#include <vtkSmartPointer.h>

#include <vector>

class vtkUnstructuredGrid;

namespace ligsim::render {

/// `criterion`: one value per triangle (Tearing::element_criterion).
vtkSmartPointer<vtkUnstructuredGrid> membrane_frame(const membrane::TearSimulation& simulation,
                                                    const std::vector<double>& criterion);

} // namespace ligsim::render
