#pragma once
/// @brief Checks a legacy .vtk file before VTK's reader sees it: VTK 9.1's vtkPolyDataReader
/// crashes (SIGSEGV in vtkDataReader::ReadString) on a truncated file and trusts its counts.

#include <filesystem>

namespace ligsim::io {

/// Throws InputError naming the file, what is wrong and where (line, or byte offset after binary
/// data) unless the file is a whole legacy POLYDATA file: the `# vtk DataFile Version` line,
/// a title, ASCII or BINARY, `DATASET POLYDATA`, then sections we know (POINTS, VERTICES, LINES,
/// POLYGONS, TRIANGLE_STRIPS in the old and the 5.x offsets/connectivity layout, POINT_DATA,
/// CELL_DATA with SCALARS, COLOR_SCALARS, LOOKUP_TABLE, VECTORS, NORMALS, TEXTURE_COORDINATES,
/// TENSORS, GLOBAL_IDS, PEDIGREE_IDS, FIELD, and METADATA), each holding as many values as its
/// counts announce, every cell naming existing points and the attribute counts matching the
/// point and cell counts.
void check_legacy_vtk(const std::filesystem::path& file);

} // namespace ligsim::io
