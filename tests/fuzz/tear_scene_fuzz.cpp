// libFuzzer target: the tear scene (`ligsim tear`, TOML) through membrane::load_scene. Any input
// must end in a scene or an InputError, never a crash, a hang or a sanitizer report.

#include "common/error.hpp"
#include "sim/membrane/scene/scene.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  try {
    ligsim::membrane::load_scene(ligsim::fuzz::write_input_file(data, size, ".toml"));
  } catch (const ligsim::Error& error) {
    ligsim::fuzz::rejected(error);
  }
  return 0;
}
