// libFuzzer target: label-map files (LIGSIM_FUZZ_EXTENSION, ".nrrd" or ".mha") through
// labelmap::read_label_image (ITK's readers behind it). Any input must end in a label image or
// an InputError, never a crash, a hang or a sanitizer report.

#include "common/error.hpp"
#include "stages/labelmap/label_image.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  static const std::string extension = LIGSIM_FUZZ_EXTENSION;
  try {
    ligsim::labelmap::read_label_image(ligsim::fuzz::write_input_file(data, size, extension));
  } catch (const ligsim::Error& error) {
    ligsim::fuzz::rejected(error);
  }
  return 0;
}
