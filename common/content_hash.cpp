#include "common/content_hash.hpp"

#include "common/error.hpp"

#include <array>
#include <fstream>

namespace ligsim {

ContentHash& ContentHash::add(std::string_view bytes)
{
  for (unsigned char byte : bytes) {
    m_state ^= byte;
    m_state *= 0x100000001b3ULL;
  }
  // A separator so ("ab","c") and ("a","bc") differ.
  m_state ^= 0xff;
  m_state *= 0x100000001b3ULL;
  return *this;
}

ContentHash& ContentHash::add_file(const std::filesystem::path& file)
{
  std::ifstream in(file, std::ios::binary);
  if (!in)
    fail("cannot read '{}'", file.string());
  std::array<char, 1 << 16> buffer{};
  while (in) {
    in.read(buffer.data(), buffer.size());
    const auto count = static_cast<std::size_t>(in.gcount());
    for (std::size_t i = 0; i < count; ++i) {
      m_state ^= static_cast<unsigned char>(buffer[i]);
      m_state *= 0x100000001b3ULL;
    }
  }
  return add("");
}

std::string ContentHash::hex() const
{
  return fmt::format("{:016x}", m_state);
}

} // namespace ligsim
