// libFuzzer target: the simulate scene (`ligsim simulate`, TOML) through parse_scene. Any input
// must end in a scene or an InputError, never a crash, a hang or a sanitizer report.

#include "common/error.hpp"
#include "sim/scene/scene.hpp"
#include "tests/fuzz/fuzz_support.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    ligsim::sim::parse_scene(text, "/nonexistent", "fuzz.toml");
  } catch (const ligsim::Error& error) {
    ligsim::fuzz::rejected(error);
  }
  return 0;
}
