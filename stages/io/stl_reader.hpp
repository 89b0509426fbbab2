#pragma once
/// @brief Our own STL reader (ASCII and binary). VTK 9.1's vtkSTLReader guesses the kind from the
/// first bytes and trusts the announced triangle count (a binary file starting with "solid"
/// made it allocate 8 GB), so STL never reaches it.

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <filesystem>

namespace ligsim::io {

/// Reads an STL file: binary when its size is exactly 84 + 50 n bytes with n from bytes 80..83
/// (even if it starts with "solid", as some exporters write), ASCII when it starts with
/// "solid", otherwise a damaged binary file. Each triangle gets its own three points (the
/// caller merges). Throws InputError naming the file, what is wrong and where (line of an ASCII
/// file, byte counts of a binary one).
vtkSmartPointer<vtkPolyData> read_stl(const std::filesystem::path& file);

} // namespace ligsim::io
