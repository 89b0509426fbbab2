#pragma once
/// @brief VTK files in and out: the writer follows the extension, every write is atomic.

#include <vtkSmartPointer.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

class vtkDataObject;
class vtkObject;
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

/// Keeps VTK's own error and warning messages off stderr (ligsim reports errors itself, in one
/// line); call once at start-up.
void silence_vtk_output();

/// Collects the error messages a VTK algorithm raises while it runs, so they can be reported
/// as part of ligsim's own error.
class VtkErrorTrap {
public:
  explicit VtkErrorTrap(vtkObject* watched);
  ~VtkErrorTrap();
  VtkErrorTrap(const VtkErrorTrap&) = delete;
  VtkErrorTrap& operator=(const VtkErrorTrap&) = delete;

  bool caught() const { return !m_message.empty(); }
  /// The first error, reduced to one line without VTK's source location prefix.
  const std::string& message() const { return m_message; }

private:
  vtkObject* m_watched;
  unsigned long m_tag = 0;
  std::string m_message;
};

} // namespace ligsim
