#pragma once
/// @brief Checks the counts in a VTP (VTK XML PolyData) file before VTK's reader sees it: VTK
/// 9.1's vtkXMLReader sizes its arrays from them unchecked (NumberOfComponents="-3" ends in an
/// uncaught std::length_error).

#include <filesystem>

namespace ligsim::io {

/// Throws InputError naming the file, the line and the attribute unless every
/// NumberOfComponents in the XML part (before any appended data) is a whole number from 1 to
/// 1024, and every NumberOfPoints, NumberOfVerts, NumberOfLines, NumberOfStrips, NumberOfPolys
/// and NumberOfTuples a whole number from 0 to 2^31 - 1.
void check_vtp(const std::filesystem::path& file);

} // namespace ligsim::io
