#include "common/vtk_files.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkDataObject.h>
#include <vtkDataSetWriter.h>
#include <vtkImageData.h>
#include <vtkPolyData.h>
#include <vtkStringOutputWindow.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLImageDataWriter.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtkXMLUnstructuredGridReader.h>
#include <vtkXMLUnstructuredGridWriter.h>

namespace ligsim {

namespace fs = std::filesystem;

namespace {

vtkSmartPointer<vtkXMLWriter> xml_writer_for(const std::string& extension)
{
  if (extension == ".vti")
    return vtkSmartPointer<vtkXMLImageDataWriter>::New();
  if (extension == ".vtp")
    return vtkSmartPointer<vtkXMLPolyDataWriter>::New();
  if (extension == ".vtu")
    return vtkSmartPointer<vtkXMLUnstructuredGridWriter>::New();
  return nullptr;
}

template <class Reader> auto read_xml(const fs::path& file, const char* kind)
{
  if (!fs::exists(file))
    fail("missing file '{}'", file.string());
  auto reader = vtkSmartPointer<Reader>::New();
  if (!reader->CanReadFile(file.c_str()))
    fail("'{}' is not a VTK XML {} file", file.string(), kind);
  reader->SetFileName(file.c_str());
  reader->Update();
  auto output = reader->GetOutput();
  if (output == nullptr)
    fail("cannot read '{}'", file.string());
  using Output = std::remove_pointer_t<decltype(output)>;
  vtkSmartPointer<Output> result = output;
  return result;
}

} // namespace

void write_vtk(vtkDataObject* data, const fs::path& file)
{
  const std::string extension = file.extension().string();
  AtomicFile atomic(file);
  int ok = 0;
  std::string vtk_message;
  if (auto writer = xml_writer_for(extension)) {
    const VtkErrorTrap trap(writer);
    writer->SetInputData(data);
    writer->SetFileName(atomic.temp_path().c_str());
    writer->SetDataModeToAppended();
    writer->SetCompressorTypeToZLib();
    ok = writer->Write();
    vtk_message = trap.message();
  } else if (extension == ".vtk") {
    auto writer = vtkSmartPointer<vtkDataSetWriter>::New();
    writer->SetInputData(data);
    writer->SetFileName(atomic.temp_path().c_str());
    writer->SetFileTypeToBinary();
    ok = writer->Write();
  } else {
    fail("cannot write '{}': unknown VTK extension '{}' (use .vti, .vtp, .vtu or .vtk)",
         file.string(), extension);
  }
  if (ok != 1 || !vtk_message.empty())
    fail("writing '{}' failed{}{}", file.string(), vtk_message.empty() ? "" : ": ", vtk_message);
  atomic.commit();
}

vtkSmartPointer<vtkImageData> read_vti(const fs::path& file)
{
  return read_xml<vtkXMLImageDataReader>(file, "image (.vti)");
}

vtkSmartPointer<vtkPolyData> read_vtp(const fs::path& file)
{
  return read_xml<vtkXMLPolyDataReader>(file, "poly data (.vtp)");
}

vtkSmartPointer<vtkUnstructuredGrid> read_vtu(const fs::path& file)
{
  return read_xml<vtkXMLUnstructuredGridReader>(file, "unstructured grid (.vtu)");
}

void silence_vtk_output()
{
  auto quiet = vtkSmartPointer<vtkStringOutputWindow>::New();
  vtkOutputWindow::SetInstance(quiet);
}

VtkErrorTrap::VtkErrorTrap(vtkObject* watched)
    : m_watched(watched)
{
  auto callback = vtkSmartPointer<vtkCallbackCommand>::New();
  callback->SetClientData(this);
  callback->SetCallback([](vtkObject*, unsigned long, void* client, void* data) {
    auto* trap = static_cast<VtkErrorTrap*>(client);
    if (!trap->m_message.empty() || data == nullptr)
      return;
    std::string text = static_cast<const char*>(data);
    // VTK prefixes "ERROR: In file, line N\nClass (0x...): "; keep what follows the last ": ".
    const auto colon = text.rfind("): ");
    if (colon != std::string::npos)
      text = text.substr(colon + 3);
    for (char& c : text)
      if (c == '\n' || c == '\r')
        c = ' ';
    while (!text.empty() && text.back() == ' ')
      text.pop_back();
    trap->m_message = text;
  });
  m_tag = watched->AddObserver(vtkCommand::ErrorEvent, callback);
}

VtkErrorTrap::~VtkErrorTrap()
{
  m_watched->RemoveObserver(m_tag);
}

} // namespace ligsim
