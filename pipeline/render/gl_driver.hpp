#pragma once
/// @brief The Mesa DRI driver (".../dri/<name>_dri.so") behind VTK's OpenGL windows, and keeping
/// it loaded once a picture has been drawn.

#include <string>
#include <vector>

namespace ligsim::render {

/// The paths of the Mesa DRI drivers this process has loaded now (none before the first render,
/// or where VTK renders without Mesa).
std::vector<std::string> loaded_gl_drivers();

/// Keeps every DRI driver loaded now mapped until the process exits. libGLX_mesa unloads the
/// driver when a VTK window closes its X connection; the few blocks only the driver's globals
/// point to (two 56-byte blocks of llvmpipe) then count as leaks for LeakSanitizer in every run
/// that renders, and its report cannot even name the unloaded module. Keeping it costs nothing
/// measurable (the picture tests take 0.7-0.9 s either way) and spares the next picture a
/// reload. Each driver is pinned once; later calls only look.
void keep_gl_drivers_loaded();

} // namespace ligsim::render
