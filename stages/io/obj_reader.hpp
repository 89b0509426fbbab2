#pragma once
/// @brief Our own Wavefront OBJ reader: vtkOBJReader 9.1 reads out of bounds on faces such as
/// `f 1 3 2333/`, and that cannot be prevented from outside, so OBJ never reaches it.

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <filesystem>

namespace ligsim::io {

/// Reads the vertices (`v x y z [w]`, further numbers such as colours ignored) and faces
/// (`f` with three or more of `v`, `v/vt`, `v//vn`, `v/vt/vn`; negative indices count back from
/// the last one defined) of an OBJ file; every other statement is ignored. Each index must name
/// a vertex, texture coordinate or normal defined above it. Throws InputError naming the file,
/// the line and what is wrong.
vtkSmartPointer<vtkPolyData> read_obj(const std::filesystem::path& file);

} // namespace ligsim::io
