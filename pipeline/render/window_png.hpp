#pragma once
/// @brief The last step of every picture: render an off-screen VTK window and write its pixels
/// as a PNG, atomically.

#include <filesystem>

class vtkRenderWindow;

namespace ligsim::render {

/// Makes `window` an off-screen window of width x height pixels. Throws Error if VTK's OpenGL
/// back-end is not registered (the library was built without vtk_module_autoinit).
void prepare_offscreen_window(vtkRenderWindow* window, int width, int height);

/// Renders `window` and writes its RGB pixels to `png` through a temporary sibling. Throws Error
/// with VTK's message if rendering fails, InputError if the file cannot be written.
void write_window_png(vtkRenderWindow* window, const std::filesystem::path& png);

} // namespace ligsim::render
