#pragma once
/// @brief Helpers of the fuzz targets: the input as a file (for readers that take a path) and
/// the rejection message on stderr when LIGSIM_FUZZ_VERBOSE is set (to see why seeds fail).

#include "common/error.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace ligsim::fuzz {

/// The input bytes in one temporary file per process, with the extension that picks the reader;
/// the file goes when the process ends.
inline std::filesystem::path write_input_file(const std::uint8_t* data, std::size_t size,
                                              const std::string& extension)
{
  struct InputFile {
    std::filesystem::path path;
    ~InputFile()
    {
      std::error_code ignored;
      std::filesystem::remove(path, ignored);
    }
  };
  static InputFile input{std::filesystem::temp_directory_path() /
                         ("ligsim_fuzz_" + std::to_string(::getpid()) + extension)};
  const std::filesystem::path& file = input.path;
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return file;
}

/// A clear error is the right answer to bad input; shown only with LIGSIM_FUZZ_VERBOSE.
inline void rejected(const Error& error)
{
  static const bool verbose = std::getenv("LIGSIM_FUZZ_VERBOSE") != nullptr;
  if (verbose)
    std::fprintf(stderr, "rejected: %s\n", error.what());
}

} // namespace ligsim::fuzz
