#include "common/vdb_file_id.hpp"

#include "common/content_hash.hpp"
#include "common/error.hpp"

#include <fstream>
#include <iterator>
#include <string>

namespace ligsim {

namespace {

// OpenVDB's header: magic number " BDV\0\0\0\0" (8 bytes), file format version (4), library
// major and minor version (4 + 4), "has grid offsets" (1), then the UUID as 36 characters
// ("xxxxxxxx-xxxx-xxxx-xxxx-xxxxxxxxxxxx").
constexpr std::size_t kUuidOffset = 21;
constexpr std::size_t kUuidLength = 36;

bool has_text_uuid(const std::string& bytes)
{
  if (bytes.size() < kUuidOffset + kUuidLength || bytes.compare(0, 4, " BDV") != 0)
    return false;
  for (std::size_t dash : {8, 13, 18, 23})
    if (bytes[kUuidOffset + dash] != '-')
      return false;
  return true;
}

} // namespace

void make_vdb_file_id_reproducible(const std::filesystem::path& vdb_file)
{
  std::fstream file(vdb_file, std::ios::in | std::ios::out | std::ios::binary);
  if (!file)
    fail("cannot open '{}'", vdb_file.string());
  const std::string bytes{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
  if (!has_text_uuid(bytes))
    fail("'{}' has no OpenVDB header with a file id", vdb_file.string());
  const std::string_view content = std::string_view(bytes).substr(kUuidOffset + kUuidLength);
  // 32 hex digits from two 64-bit hashes of everything after the id.
  const std::string digits =
      ContentHash().add(content).hex() + ContentHash().add("ligsim vdb file id").add(content).hex();
  const std::string uuid = digits.substr(0, 8) + "-" + digits.substr(8, 4) + "-" +
                           digits.substr(12, 4) + "-" + digits.substr(16, 4) + "-" +
                           digits.substr(20, 12);
  file.clear();
  file.seekp(static_cast<std::streamoff>(kUuidOffset));
  file.write(uuid.data(), static_cast<std::streamsize>(uuid.size()));
  if (!file)
    fail("cannot write '{}'", vdb_file.string());
}

} // namespace ligsim
