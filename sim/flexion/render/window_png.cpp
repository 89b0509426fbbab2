#include "sim/flexion/render/window_png.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/vtk_files.hpp"

#include <vtkNew.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkPNGWriter.h>
#include <vtkRenderWindow.h>
#include <vtkWindowToImageFilter.h>

#include <dlfcn.h>
#include <link.h>
#include <string>
#include <vector>

namespace ligsim::sim {

namespace {

/// Keeps every Mesa DRI driver now loaded (".../dri/<name>_dri.so") mapped until the process
/// exits. libGLX_mesa unloads the driver when a VTK window closes its X connection; the few
/// blocks only the driver's globals point to (two 56-byte blocks of llvmpipe) then count as
/// leaks for LeakSanitizer in every run that renders, and its report cannot even name the
/// unloaded module. Keeping it costs nothing measurable (the picture tests take 0.7-0.9 s
/// either way) and spares the next picture a reload.
void keep_gl_driver_loaded()
{
  std::vector<std::string> drivers;
  dl_iterate_phdr(
      [](dl_phdr_info* module, size_t, void* found) {
        const std::string path = module->dlpi_name ? module->dlpi_name : "";
        const std::string suffix = "_dri.so";
        if (path.size() > suffix.size() &&
            path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0)
          static_cast<std::vector<std::string>*>(found)->push_back(path);
        return 0;
      },
      &drivers);
  // Outside the iteration, which holds the loader's lock. The handle is never closed: that
  // reference, and RTLD_NODELETE, are the point.
  for (const std::string& driver : drivers)
    dlopen(driver.c_str(), RTLD_LAZY | RTLD_NOLOAD | RTLD_NODELETE);
}

} // namespace

void prepare_offscreen_window(vtkRenderWindow* window, int width, int height)
{
  if (!vtkOpenGLRenderWindow::SafeDownCast(window))
    fail<Error>("VTK has no OpenGL render window (got {}): the program was linked without "
                "vtk_module_autoinit for VTK::RenderingOpenGL2",
                window ? window->GetClassName() : "none");
  constexpr int kMaxPixels = 16384;
  if (width < 16 || height < 16 || width > kMaxPixels || height > kMaxPixels)
    fail("a picture must be 16 to {} pixels wide and high, got {} x {}", kMaxPixels, width, height);
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(width, height);
}

void write_window_png(vtkRenderWindow* window, const std::filesystem::path& png)
{
  {
    VtkErrorTrap trap(window);
    window->Render();
    if (trap.caught())
      fail<Error>("cannot render '{}' with OpenGL: {}", png.string(), trap.message());
  }
  keep_gl_driver_loaded();
  vtkNew<vtkWindowToImageFilter> capture;
  capture->SetInput(window);
  capture->SetInputBufferTypeToRGB();
  capture->ReadFrontBufferOff();
  capture->Update();

  AtomicFile file(png);
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputConnection(capture->GetOutputPort());
  writer->SetFileName(file.temp_path().string().c_str());
  {
    VtkErrorTrap trap(writer);
    writer->Write();
    if (trap.caught() || writer->GetErrorCode() != 0)
      fail("cannot write '{}'{}", png.string(), trap.caught() ? ": " + trap.message() : "");
  }
  file.commit();
}

} // namespace ligsim::sim
