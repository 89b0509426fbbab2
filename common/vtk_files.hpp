#pragma once
/// @brief VTK files in and out: the writer follows the extension, every write is atomic.

#include <vtkSmartPointer.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

class vtkDataObject;
class vtkImageData;
class vtkPolyData;
class vtkUnstructuredGrid;

namespace ligsim {

/// Writes `data` to `file` (.vti, .vtp, .vtu as binary XML with zlib compression; .vtk legacy),
/// through a temporary sibling. Throws InputError on an unknown extension or a failed write.
void write_vtk(vtkDataObject* data, const std::filesystem::path& file);

/// Reads a file written by write_vtk (or any VTK XML / legacy file of that type).
/// Throws InputError naming the file if it is missing or unreadable.
vtkSmartPointer<vtkImageData> read_vti(const std::filesystem::path& file);
vtkSmartPointer<vtkPolyData> read_vtp(const std::filesystem::path& file);
vtkSmartPointer<vtkUnstructuredGrid> read_vtu(const std::filesystem::path& file);

/// A ParaView collection file: (time, file relative to the .pvd) pairs.
void write_pvd(const std::filesystem::path& file,
               const std::vector<std::pair<double, std::string>>& steps);

} // namespace ligsim
