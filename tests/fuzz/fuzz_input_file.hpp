#pragma once
/// @brief For fuzz targets whose reader takes a path: the input bytes written to one temporary
/// file per process, with the extension that picks the reader.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace ligsim::fuzz {

inline std::filesystem::path write_input_file(const std::uint8_t* data, std::size_t size,
                                              const std::string& extension)
{
  const std::filesystem::path file = std::filesystem::temp_directory_path() /
                                     ("ligsim_fuzz_" + std::to_string(::getpid()) + extension);
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return file;
}

} // namespace ligsim::fuzz
