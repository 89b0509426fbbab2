// libFuzzer target: one surface format (LIGSIM_FUZZ_EXTENSION, ".stl" ...) through
// read_surface. Any input must end in a surface or an InputError, never a crash, a hang or a
// sanitizer report. The reader takes a path (VTK's readers do), so the bytes go through a file.

#include "common/error.hpp"
#include "stages/io/surface_reader.hpp"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  static const std::filesystem::path file =
      std::filesystem::temp_directory_path() /
      ("ligsim_fuzz_" + std::to_string(::getpid()) + LIGSIM_FUZZ_EXTENSION);
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    ligsim::io::read_surface(file);
  } catch (const ligsim::Error&) {
    // a clear error is the right answer to bad input
  }
  return 0;
}
