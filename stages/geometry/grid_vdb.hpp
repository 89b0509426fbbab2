#pragma once
/// @brief Our sparse grids as OpenVDB (.vdb) files, for Houdini and Blender users and as the
/// stages' own storage between runs (read back without the dense box).

#include "stages/geometry/grid.hpp"

#include <filesystem>
#include <string>

namespace ligsim::vdb {

/// Writes the stored bricks of `grid` (atomically) as a float grid named `name`; voxels equal
/// to the background are inactive.
void write_grid(const ScalarGrid& grid, const std::string& name, const std::filesystem::path& file);

/// Reads a grid written by write_grid(). Throws InputError naming the file if it is missing,
/// unreadable or lacks the grid.
ScalarGrid read_grid(const std::filesystem::path& file, const std::string& name);

} // namespace ligsim::vdb
