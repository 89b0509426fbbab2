#pragma once
/// A small synthetic knee for the CLI tests: straight ligaments (cylinders along +z from z = 0 to
/// z = 16) between a femur box above and a tibia box (and a fibula box) below.

#include "common/vtk_files.hpp"
#include "stages/io/vtk_convert.hpp"
#include "stages/synthetic/shapes.hpp"

#include <vtkPolyData.h>

#include <filesystem>

namespace ligsim::test {

/// A straight ligament of `radius_mm`, from z = 0 to z = 16 at (x_mm, 0).
inline void write_straight_ligament(double radius_mm, double x_mm,
                                    const std::filesystem::path& file)
{
  synthetic::Shape shape = synthetic::cylinder(radius_mm, 16.0, 24);
  shape.surface.V.col(0).array() += x_mm;
  write_vtk(io::to_polydata(shape.surface), file);
}

/// femur.vtp (z from 16.2 to 30), tibia.vtp (x from -15 to 9, z from -14 to -0.2) and
/// fibula.vtp (x from 10 to 16) in `dir`.
inline void write_knee_bones(const std::filesystem::path& dir)
{
  write_vtk(io::to_polydata(synthetic::box({-15, -10, 16.2}, {20, 10, 30})), dir / "femur.vtp");
  write_vtk(io::to_polydata(synthetic::box({-15, -10, -14}, {9, 10, -0.2})), dir / "tibia.vtp");
  write_vtk(io::to_polydata(synthetic::box({10, -5, -14}, {16, 5, -0.2})), dir / "fibula.vtp");
}

} // namespace ligsim::test
