#pragma once
/// @brief Reading segmented surfaces: STL (ASCII and binary), OBJ, PLY, VTP and legacy VTK, mm;
/// glTF (.glb, .gltf; metres, converted to mm), one mesh of it named by `file.glb#name`.

#include "common/mesh.hpp"

#include <Eigen/Core>

#include <filesystem>
#include <map>
#include <string>

namespace ligsim::io {

/// Reads a triangle surface. Polygons are triangulated, coincident points merged, unused points
/// dropped. A glTF path may end in `#name` to choose a mesh, or `#A+B+C` to join several into
/// one surface (see split_surface_path and read_gltf). Throws InputError naming the file on: a
/// missing file, an unknown extension, a file with no triangles, a non-finite coordinate (with the
/// vertex index). If `point_arrays` is given, it receives the file's one-component point-data
/// arrays, by name, one value per (merged) vertex.
TriangleSurface read_surface(const std::filesystem::path& file,
                             std::map<std::string, Eigen::VectorXd>* point_arrays = nullptr);

/// Throws InputError unless `surface` is a closed, consistently oriented 2-manifold without
/// self-intersections; the message gives the count and the location of the defects.
/// `what` names the surface in the message ("ligament surface 'mcl.stl'").
void require_closed_manifold(const TriangleSurface& surface, const std::string& what);

/// Flips every triangle if the enclosed volume is negative, so normals face outward.
void orient_outward(TriangleSurface& surface);

} // namespace ligsim::io
