#pragma once
/// @brief Content hashes that key the pipeline's cache: same inputs and parameters, same key.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace ligsim {

/// Incremental 64-bit FNV-1a. Not cryptographic: it detects change, not tampering.
class ContentHash {
public:
  ContentHash& add(std::string_view bytes);
  /// Adds a file's bytes; throws InputError if it cannot be read.
  ContentHash& add_file(const std::filesystem::path& file);
  /// 16 hex digits.
  std::string hex() const;

private:
  std::uint64_t m_state = 0xcbf29ce484222325ULL;
};

} // namespace ligsim
