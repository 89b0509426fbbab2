#include "common/atomic_file.hpp"
#include "common/error.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

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

TEST(AtomicFile, NextWriteRemovesTemporaryOfAKilledWriter)
{
  const fs::path dir = fresh_dir("atomic_orphan");
  // A process that has ended, as one killed halfway through its write.
  const pid_t gone = ::fork();
  ASSERT_GE(gone, 0);
  if (gone == 0)
    ::_exit(0);
  ASSERT_EQ(::waitpid(gone, nullptr, 0), gone);
  const fs::path orphan = dir / (".a.tmp-" + std::to_string(gone) + ".txt");
  const fs::path running = dir / (".a.tmp-" + std::to_string(::getppid()) + ".txt");
  const fs::path other_target = dir / (".b.tmp-" + std::to_string(gone) + ".txt");
  for (const fs::path& file : {orphan, running, other_target})
    std::ofstream(file) << "half";

  ligsim::write_text_atomically(dir / "a.txt", "good");
  EXPECT_EQ(read_all(dir / "a.txt"), "good");
  EXPECT_FALSE(fs::exists(orphan));
  EXPECT_TRUE(fs::exists(running)) << "a writer still running keeps its temporary";
  EXPECT_TRUE(fs::exists(other_target)) << "only the written target's temporaries go";
}
