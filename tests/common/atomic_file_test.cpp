#include "common/atomic_file.hpp"
#include "common/error.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

namespace fs = std::filesystem;

namespace {

std::string read_all(const fs::path& file)
{
  std::ifstream in(file);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

fs::path fresh_dir(const std::string& name)
{
  fs::path dir = fs::temp_directory_path() / ("ligsim_test_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

} // namespace

TEST(AtomicFile, CommitReplacesTarget)
{
  const fs::path dir = fresh_dir("atomic_commit");
  ligsim::write_text_atomically(dir / "a.txt", "old");
  ligsim::write_text_atomically(dir / "a.txt", "new");
  EXPECT_EQ(read_all(dir / "a.txt"), "new");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST(AtomicFile, AbandonedWriteLeavesGoodFileUntouched)
{
  const fs::path dir = fresh_dir("atomic_abandon");
  ligsim::write_text_atomically(dir / "a.txt", "good");
  {
    ligsim::AtomicFile file(dir / "a.txt");
    std::ofstream(file.temp_path()) << "half";
    // no commit: as if the writer threw
  }
  EXPECT_EQ(read_all(dir / "a.txt"), "good");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST(AtomicFile, CommitWithoutWriteIsAnError)
{
  const fs::path dir = fresh_dir("atomic_nothing");
  ligsim::AtomicFile file(dir / "a.txt");
  EXPECT_THROW(file.commit(), ligsim::InputError);
  EXPECT_FALSE(fs::exists(dir / "a.txt"));
}
