#include "common/vdb_file_id.hpp"

#include "common/error.hpp"

#include <gtest/gtest.h>

#include <cctype>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

/// The first 21 bytes of an OpenVDB file (magic, versions, offsets flag) as OpenVDB 10 writes
/// them, a UUID, then `content` standing for the grids.
std::string vdb_bytes(const std::string& uuid, const std::string& content)
{
  const std::string header(" BDV\0\0\0\0\xe0\0\0\0\x0a\0\0\0\0\0\0\0\x01", 21);
  return header + uuid + content;
}

fs::path write_file(const std::string& name, const std::string& bytes)
{
  const fs::path file =
      fs::temp_directory_path() / ("ligsim_vdb_id_" + std::to_string(::getpid()) + "_" + name);
  std::ofstream(file, std::ios::binary) << bytes;
  return file;
}

std::string read_all(const fs::path& file)
{
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

} // namespace

TEST(VdbFileId, SameGridsGiveTheSameBytesWhateverTheRandomId)
{
  const std::string grids = std::string("Tree_float_5_4_3\0\x01\x02", 19);
  const fs::path a = write_file("a.vdb", vdb_bytes("0fa408c5-7541-496b-9d97-fd615e0ed679", grids));
  const fs::path b = write_file("b.vdb", vdb_bytes("9c1d2e3f-0000-4a4a-8b8b-123456789abc", grids));
  const fs::path c = write_file("c.vdb", vdb_bytes("0fa408c5-7541-496b-9d97-fd615e0ed679", "x"));
  for (const fs::path& file : {a, b, c})
    ligsim::make_vdb_file_id_reproducible(file);
  EXPECT_EQ(read_all(a), read_all(b));
  EXPECT_NE(read_all(a).substr(21, 36), read_all(c).substr(21, 36));
  // Still a UUID in OpenVDB's text form, and nothing else changed.
  const std::string id = read_all(a).substr(21, 36);
  for (std::size_t i = 0; i < id.size(); ++i)
    EXPECT_TRUE((i == 8 || i == 13 || i == 18 || i == 23) ? id[i] == '-'
                                                          : std::isxdigit(id[i]) != 0)
        << id;
  EXPECT_EQ(read_all(a).substr(0, 21), vdb_bytes("", "").substr(0, 21));
  EXPECT_EQ(read_all(a).substr(57), grids);
  for (const fs::path& file : {a, b, c})
    fs::remove(file);
}

TEST(VdbFileId, AFileWithoutAnOpenVdbHeaderIsAnError)
{
  const fs::path file = write_file("plain.vdb", std::string(80, 'x'));
  EXPECT_THROW(ligsim::make_vdb_file_id_reproducible(file), ligsim::InputError);
  EXPECT_EQ(read_all(file), std::string(80, 'x'));
  EXPECT_THROW(ligsim::make_vdb_file_id_reproducible(file.string() + ".missing"),
               ligsim::InputError);
  fs::remove(file);
}
