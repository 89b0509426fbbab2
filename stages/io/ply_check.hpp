#pragma once
/// @brief Checks a PLY file before VTK's reader sees it: VTK 9.1's vtkPLYReader crashes
/// (SIGSEGV) on a truncated header or body, and trusts the element counts.

#include <filesystem>

namespace ligsim::io {

/// Throws InputError naming the file, what is wrong and where (line, or byte offset in binary
/// data) unless: the header is whole (`ply`, `format ascii|binary_little_endian|
/// binary_big_endian 1.0`, elements with known property types, `end_header`); a `vertex`
/// element has x, y and z and a `face` element a vertex_indices list of at most 255 corners;
/// and the body holds every announced element (binary: bytes, lists walked; ASCII: one line of
/// numbers per element with the right count).
void check_ply(const std::filesystem::path& file);

} // namespace ligsim::io
