// libFuzzer target: the flexion config (`ligsim flexion --config`, TOML) through
// parse_flexion_config. Any input must end in settings or an InputError, never a crash, a hang
// or a sanitizer report.

#include "common/error.hpp"
#include "sim/flexion/flexion_config.hpp"
#include "sim/flexion/flexion_settings.hpp"
#include "tests/fuzz/fuzz_support.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    ligsim::sim::FlexionSettings settings;
    ligsim::sim::parse_flexion_config(text, "/nonexistent", "fuzz.toml", settings);
  } catch (const ligsim::Error& error) {
    ligsim::fuzz::rejected(error);
  }
  return 0;
}
