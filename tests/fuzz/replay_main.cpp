// Driver for builds without libFuzzer (gcc, the normal suite): runs every file given on the
// command line (files or folders) through LLVMFuzzerTestOneInput, then deterministic mutations
// of each: truncations, flipped bytes, a doubled tail. A crash fails the test.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

void run(const std::vector<std::uint8_t>& bytes)
{
  LLVMFuzzerTestOneInput(bytes.data(), bytes.size());
}

void mutate_and_run(const std::vector<std::uint8_t>& seed)
{
  run(seed);
  for (int part = 0; part < 8; ++part)
    run({seed.begin(), seed.begin() + static_cast<std::ptrdiff_t>(seed.size() * part / 8)});
  for (std::size_t i = 0; i < seed.size(); i += std::max<std::size_t>(1, seed.size() / 16)) {
    std::vector<std::uint8_t> flipped = seed;
    flipped[i] ^= 0xff;
    run(flipped);
  }
  std::vector<std::uint8_t> doubled = seed;
  doubled.insert(doubled.end(), seed.begin() + static_cast<std::ptrdiff_t>(seed.size() / 2),
                 seed.end());
  run(doubled);
}

} // namespace

int main(int argc, char** argv)
{
  int files = 0;
  for (int i = 1; i < argc; ++i) {
    std::vector<std::filesystem::path> paths;
    if (std::filesystem::is_directory(argv[i])) {
      for (const auto& entry : std::filesystem::directory_iterator(argv[i]))
        paths.push_back(entry.path());
    } else {
      paths.emplace_back(argv[i]);
    }
    for (const auto& path : paths) {
      std::ifstream in(path, std::ios::binary);
      mutate_and_run({std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()});
      ++files;
    }
  }
  std::printf("replayed %d seed files with their mutations\n", files);
  return files > 0 ? 0 : 1;
}
