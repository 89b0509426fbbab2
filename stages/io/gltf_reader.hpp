#pragma once
/// @brief Reading one mesh of a glTF 2.0 file (.glb, .gltf) with VTK's reader, in mm.

#include <vtkSmartPointer.h>

#include <filesystem>
#include <string>

class vtkPolyData;

namespace ligsim::io {

/// The mesh `name` of a glTF file: the scene's node of that name, else the node drawing the mesh
/// of that name; with `name` empty, the file's only mesh. Node transforms are applied and the
/// coordinates converted from metres (glTF's unit) to millimetres; the primitives come as they
/// are (triangles, strips, fans; points and lines too), their vertices not yet merged.
/// Throws InputError naming the file: what check_gltf finds; an unknown name or a missing name
/// in a file of several meshes (listing the names the file has); a name given twice; VTK's
/// errors.
vtkSmartPointer<vtkPolyData> read_gltf(const std::filesystem::path& file, const std::string& name);

} // namespace ligsim::io
