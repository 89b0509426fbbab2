#include "pipeline/render/window_png.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/vtk_files.hpp"
#include "pipeline/render/gl_driver.hpp"

#include <vtkNew.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkPNGWriter.h>
#include <vtkRenderWindow.h>
#include <vtkWindowToImageFilter.h>

namespace ligsim::render {

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
  keep_gl_drivers_loaded();
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

} // namespace ligsim::render
