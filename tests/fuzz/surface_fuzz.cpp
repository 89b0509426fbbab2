// libFuzzer target: one surface format (LIGSIM_FUZZ_EXTENSION, ".stl" ...) through
// read_surface. Any input must end in a surface or an InputError, never a crash, a hang or a
// sanitizer report. The reader takes a path (VTK's readers do), so the bytes go through a file.

#include "common/error.hpp"
#include "stages/io/surface_reader.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  static const std::string extension = LIGSIM_FUZZ_EXTENSION;
  try {
    ligsim::io::read_surface(ligsim::fuzz::write_input_file(data, size, extension));
  } catch (const ligsim::Error& error) {
    ligsim::fuzz::rejected(error);
  }
  return 0;
}
