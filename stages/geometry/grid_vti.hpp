#pragma once
/// @brief Our sparse grids as VTK XML image files (.vti) for ParaView, written slab by slab.

#include "stages/geometry/grid.hpp"

#include <filesystem>
#include <string>

namespace ligsim {

/// Writes `grid` (atomically) as VTK XML ImageData with one point array `name`: appended
/// binary data, zlib-compressed one z-slab per block, produced one slab at a time from the
/// sparse grid, so the dense box is never held in memory (a slab is dims.x * dims.y values).
/// ParaView and vtkXMLImageDataReader read it as any other .vti. T: float or std::uint8_t.
template <class T>
void write_vti(const Grid<T>& grid, const std::string& name, const std::filesystem::path& file);

} // namespace ligsim
