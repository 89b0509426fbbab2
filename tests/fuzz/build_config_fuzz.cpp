// libFuzzer target: the build config (`ligsim build --config`, TOML) through load_build_config.
// Any input must end in a config or an InputError, never a crash, a hang or a sanitizer report.

#include "common/error.hpp"
#include "pipeline/stage_graph/build_config.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  try {
    ligsim::pipeline::load_build_config(ligsim::fuzz::write_input_file(data, size, ".toml"));
  } catch (const ligsim::Error& error) {
    ligsim::fuzz::rejected(error);
  }
  return 0;
}
