#include "common/error.hpp"
#include "sim/flexion/render/offscreen_display.hpp"

#include <gtest/gtest.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace fs = std::filesystem;
using ligsim::sim::OffscreenDisplay;

namespace {

/// Sets (or unsets, with nullopt) an environment variable for one scope.
class ScopedEnv {
public:
  ScopedEnv(const char* name, std::optional<std::string> value)
      : m_name(name)
  {
    if (const char* old = std::getenv(name))
      m_old = old;
    if (value)
      ::setenv(name, value->c_str(), 1);
    else
      ::unsetenv(name);
  }
  ~ScopedEnv()
  {
    if (m_old)
      ::setenv(m_name.c_str(), m_old->c_str(), 1);
    else
      ::unsetenv(m_name.c_str());
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

private:
  std::string m_name;
  std::optional<std::string> m_old;
};

/// True while a process with this id exists (zombies included: an unreaped Xvfb counts).
bool process_exists(pid_t pid)
{
  return fs::exists("/proc/" + std::to_string(pid));
}

/// True while a process with this id runs (exists and is not a zombie).
bool process_runs(pid_t pid)
{
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(stat, line))
    return false;
  const size_t name_end = line.rfind(')');
  return name_end != std::string::npos && name_end + 2 < line.size() && line[name_end + 2] != 'Z';
}

/// Xvfb processes whose parent is this process (running or not yet reaped).
int xvfb_children()
{
  int n = 0;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    std::ifstream stat(entry.path() / "stat");
    std::string line;
    if (!std::getline(stat, line) || line.find("(Xvfb)") == std::string::npos)
      continue;
    std::istringstream fields(line.substr(line.rfind(')') + 2));
    char state = 0;
    pid_t parent = 0;
    fields >> state >> parent;
    n += parent == ::getpid() ? 1 : 0;
  }
  return n;
}

/// A fresh folder for one test's files, removed at the end of the test (set
/// LIGSIM_KEEP_TEST_PICTURES=1 to keep them for a look).
class TestDir {
public:
  explicit TestDir(const std::string& name)
      : m_path(fs::temp_directory_path() /
               ("ligsim_render_test_" + name + "_" + std::to_string(::getpid())))
  {
    fs::remove_all(m_path);
    fs::create_directories(m_path);
  }
  ~TestDir()
  {
    if (!std::getenv("LIGSIM_KEEP_TEST_PICTURES")) {
      std::error_code ignored;
      fs::remove_all(m_path, ignored);
    }
  }
  TestDir(const TestDir&) = delete;
  TestDir& operator=(const TestDir&) = delete;
  const fs::path& path() const { return m_path; }

private:
  fs::path m_path;
};

} // namespace

TEST(OffscreenDisplay, StartsXvfbTwiceAndLeavesNoServer)
{
  ScopedEnv no_display("DISPLAY", std::nullopt);
  for (int round = 0; round < 2; ++round) {
    pid_t pid = 0;
    {
      OffscreenDisplay display;
      ASSERT_TRUE(display.started_server()) << "round " << round;
      pid = display.server_pid();
      ASSERT_GT(pid, 0);
      EXPECT_TRUE(process_exists(pid));
      ASSERT_NE(std::getenv("DISPLAY"), nullptr);
      EXPECT_EQ(std::getenv("DISPLAY"), display.display());
      EXPECT_EQ(display.display().rfind(':', 0), 0u) << display.display();

      // A second one finds the first one's server answering and starts nothing.
      OffscreenDisplay nested;
      EXPECT_FALSE(nested.started_server());
      EXPECT_EQ(nested.display(), display.display());
    }
    EXPECT_FALSE(process_exists(pid)) << "Xvfb " << pid << " is still there (or unreaped)";
    EXPECT_EQ(std::getenv("DISPLAY"), nullptr);
  }
}

TEST(OffscreenDisplay, ServerStopsWhenAnExceptionUnwinds)
{
  ScopedEnv no_display("DISPLAY", std::nullopt);
  pid_t pid = 0;
  EXPECT_THROW(
      {
        OffscreenDisplay display;
        pid = display.server_pid();
        ligsim::fail("a picture failed");
      },
      ligsim::InputError);
  ASSERT_GT(pid, 0);
  EXPECT_FALSE(process_exists(pid));
}

TEST(OffscreenDisplay, ServerStopsWhenItsOwnerIsKilled)
{
  // A child process starts the server, reports its pid and dies by SIGKILL (no destructor).
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::close(fds[0]);
    ::unsetenv("DISPLAY");
    try {
      OffscreenDisplay display;
      const pid_t server = display.server_pid();
      if (::write(fds[1], &server, sizeof server) != sizeof server)
        ::_exit(1);
      ::raise(SIGKILL); // with the display alive
    } catch (...) {
    }
    ::_exit(1);
  }
  ::close(fds[1]);
  pid_t server = 0;
  const bool reported = ::read(fds[0], &server, sizeof server) == sizeof server;
  ::close(fds[0]);
  int status = 0;
  ::waitpid(child, &status, 0);
  ASSERT_TRUE(reported) << "the child could not start Xvfb";
  EXPECT_TRUE(WIFSIGNALED(status));
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (process_runs(server) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_FALSE(process_runs(server)) << "Xvfb " << server << " outlived its owner";
}

TEST(OffscreenDisplay, MissingOpenGLIsAClearErrorAndLeavesNoServer)
{
  // Mesa then offers OpenGL 2.1 only, too little for VTK (which would crash in its first render).
  ScopedEnv old_gl("MESA_GL_VERSION_OVERRIDE", std::string("2.1"));
  ScopedEnv no_display("DISPLAY", std::nullopt);
  try {
    OffscreenDisplay display;
    FAIL() << "expected an Error";
  } catch (const ligsim::Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("OpenGL 3.2"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  EXPECT_EQ(std::getenv("DISPLAY"), nullptr);
  EXPECT_EQ(xvfb_children(), 0);
}

TEST(OffscreenDisplay, FakeXvfbThatFailsIsReported)
{
  const TestDir test_dir("fake_xvfb");
  const fs::path& dir = test_dir.path();
  {
    std::ofstream script(dir / "Xvfb");
    script << "#!/bin/sh\necho 'Fatal server error: no screens found' >&2\nexit 1\n";
  }
  fs::permissions(dir / "Xvfb", fs::perms::owner_all);
  ScopedEnv no_display("DISPLAY", std::nullopt);
  ScopedEnv path("PATH", dir.string());
  try {
    OffscreenDisplay display;
    FAIL() << "expected an InputError";
  } catch (const ligsim::InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("no screens found"), std::string::npos) << message;
  }
  EXPECT_EQ(std::getenv("DISPLAY"), nullptr);
}

TEST(OffscreenDisplay, DisplayThatDoesNotAnswerIsReplacedAndRestored)
{
  ScopedEnv dead("DISPLAY", std::string(":917"));
  pid_t pid = 0;
  {
    OffscreenDisplay display;
    EXPECT_TRUE(display.started_server());
    EXPECT_NE(display.display(), ":917");
    pid = display.server_pid();
  }
  EXPECT_FALSE(process_exists(pid));
  ASSERT_NE(std::getenv("DISPLAY"), nullptr);
  EXPECT_EQ(std::string(std::getenv("DISPLAY")), ":917");
}

TEST(OffscreenDisplay, MissingXvfbNamesThePackage)
{
  const TestDir empty("empty_path");
  ScopedEnv no_display("DISPLAY", std::nullopt);
  ScopedEnv path("PATH", empty.path().string());
  try {
    OffscreenDisplay display;
    FAIL() << "expected an InputError";
  } catch (const ligsim::InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("apt-get install xvfb"), std::string::npos) << message;
    EXPECT_NE(message.find("--no-images"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  EXPECT_EQ(std::getenv("DISPLAY"), nullptr);
}
