#include "pipeline/render/offscreen_display.hpp"

#include "common/error.hpp"

#include <X11/Xlib.h>
#include <vtkNew.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkRenderWindow.h>

#include <algorithm>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <memory>
#include <poll.h>
#include <sstream>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace ligsim::render {

namespace {

using Clock = std::chrono::steady_clock;

/// How long Xvfb may take to report its display number.
constexpr auto kStartTimeout = std::chrono::seconds(20);
/// How long Xvfb may take to exit after SIGTERM before it gets SIGKILL.
constexpr auto kStopTimeout = std::chrono::seconds(5);

/// True if an X server accepts a connection on `display` (e.g. ":0").
bool display_answers(const std::string& display)
{
  Display* connection = XOpenDisplay(display.c_str());
  if (!connection)
    return false;
  XCloseDisplay(connection);
  return true;
}

/// Why VTK cannot render on the display named by $DISPLAY ("" if it can): VTK's OpenGL2 back-end
/// needs an OpenGL 3.2 core context and crashes in its first render without one.
std::string opengl_problem()
{
  vtkNew<vtkRenderWindow> window;
  auto* gl = vtkOpenGLRenderWindow::SafeDownCast(window);
  if (!gl)
    fail<Error>("VTK has no OpenGL render window (got {}): the program was linked without "
                "vtk_module_autoinit for VTK::RenderingOpenGL2",
                window->GetClassName());
  window->SetOffScreenRendering(1);
  if (gl->SupportsOpenGL())
    return {};
  // VTK's message is a paragraph; its first sentence after the object's address says it.
  std::string problem = gl->GetOpenGLSupportMessage();
  std::replace(problem.begin(), problem.end(), '\n', ' ');
  const size_t start = problem.find("): ");
  if (start != std::string::npos)
    problem = problem.substr(start + 3);
  problem = problem.substr(0, problem.find(". "));
  return problem.empty() ? "no OpenGL 3.2 context" : problem;
}

/// The first executable file called `name` in $PATH; empty if none.
std::string find_on_path(const std::string& name)
{
  const char* path = std::getenv("PATH");
  if (!path)
    return {};
  std::stringstream entries(path);
  std::string dir;
  while (std::getline(entries, dir, ':')) {
    if (dir.empty())
      dir = ".";
    const std::string candidate = dir + "/" + name;
    struct stat info {};
    if (::stat(candidate.c_str(), &info) == 0 && S_ISREG(info.st_mode) &&
        ::access(candidate.c_str(), X_OK) == 0)
      return candidate;
  }
  return {};
}

/// The last non-empty line of a file (Xvfb's stderr), for an error message.
std::string last_line(std::FILE* file)
{
  std::rewind(file);
  std::string line, last;
  char buffer[512];
  while (std::fgets(buffer, sizeof buffer, file)) {
    line += buffer;
    if (!line.empty() && line.back() == '\n') {
      line.pop_back();
      if (line.find_first_not_of(" \t") != std::string::npos)
        last = line;
      line.clear();
    }
  }
  if (line.find_first_not_of(" \t") != std::string::npos)
    last = line;
  return last;
}

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};

/// Reads the display number Xvfb writes to the pipe ("99\n"); -1 on EOF, error or timeout.
int read_display_number(int fd)
{
  std::string text;
  const auto deadline = Clock::now() + kStartTimeout;
  while (text.find('\n') == std::string::npos) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    if (left <= 0)
      return -1;
    pollfd request{fd, POLLIN, 0};
    const int ready = ::poll(&request, 1, static_cast<int>(left));
    if (ready < 0 && errno == EINTR)
      continue;
    if (ready <= 0)
      return -1;
    char buffer[32];
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR)
      continue;
    if (n <= 0)
      return -1;
    text.append(buffer, static_cast<size_t>(n));
  }
  try {
    return std::stoi(text);
  } catch (const std::exception&) {
    return -1;
  }
}

} // namespace

OffscreenDisplay::OffscreenDisplay()
{
  if (const char* current = std::getenv("DISPLAY")) {
    m_had_display = true;
    m_previous_display = current;
  }
  // The user's display, if it answers and gives VTK its OpenGL (not, say, ssh's indirect GLX).
  std::string why_not = "DISPLAY unset";
  if (m_had_display && !m_previous_display.empty()) {
    if (!display_answers(m_previous_display)) {
      why_not = "DISPLAY=" + m_previous_display + " does not answer";
    } else {
      const std::string problem = opengl_problem();
      if (problem.empty()) {
        m_display = m_previous_display;
        return;
      }
      why_not = "DISPLAY=" + m_previous_display + ": " + problem;
    }
  }
  start_xvfb(why_not);
  ::setenv("DISPLAY", m_display.c_str(), 1);
  std::string problem;
  try {
    problem = opengl_problem();
  } catch (...) {
    stop_xvfb();
    restore_display();
    throw;
  }
  if (!problem.empty()) {
    stop_xvfb();
    restore_display();
    fail<Error>("Xvfb on display {} gives VTK no OpenGL 3.2 ({}); install Mesa's software "
                "renderer (apt-get install libgl1-mesa-dri) or pass --no-images",
                m_display, problem);
  }
}

void OffscreenDisplay::restore_display() const
{
  if (m_had_display)
    ::setenv("DISPLAY", m_previous_display.c_str(), 1);
  else
    ::unsetenv("DISPLAY");
}

OffscreenDisplay::~OffscreenDisplay()
{
  if (!started_server())
    return;
  stop_xvfb();
  restore_display();
}

void OffscreenDisplay::start_xvfb(const std::string& why)
{
  const std::string xvfb = find_on_path("Xvfb");
  if (xvfb.empty())
    fail("cannot render pictures: no usable X display ({}) and no Xvfb on PATH; install xvfb "
         "(apt-get install xvfb) or pass --no-images",
         why);

  // Xvfb's stderr goes to an unlinked temporary file, read only if the start fails.
  std::unique_ptr<std::FILE, FileCloser> log(std::tmpfile());
  int pipe_fds[2];
  if (!log || ::pipe2(pipe_fds, O_CLOEXEC) != 0)
    fail("cannot start Xvfb: {}", std::strerror(errno));
  const int read_fd = pipe_fds[0];
  const int write_fd = pipe_fds[1];

  // Everything the child needs is prepared before fork: after it, only async-signal-safe calls.
  const std::vector<std::string> args = {xvfb,        "-displayfd", std::to_string(write_fd),
                                         "-nolisten", "tcp",        "-noreset",
                                         "-screen",   "0",          "2560x1600x24"};
  std::vector<char*> argv;
  for (const std::string& arg : args)
    argv.push_back(const_cast<char*>(arg.c_str()));
  argv.push_back(nullptr);
  const int log_fd = ::fileno(log.get());
  const pid_t parent = ::getpid();

  const pid_t pid = ::fork();
  if (pid < 0) {
    const int error = errno;
    ::close(read_fd);
    ::close(write_fd);
    fail("cannot start Xvfb: fork failed: {}", std::strerror(error));
  }
  if (pid == 0) {
    // The server dies with us, even if we are killed and no destructor runs.
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (::getppid() != parent)
      ::_exit(127);
    sigset_t none;
    ::sigemptyset(&none);
    ::sigprocmask(SIG_SETMASK, &none, nullptr);
    ::fcntl(write_fd, F_SETFD, 0); // the display number's pipe survives exec
    const int null_fd = ::open("/dev/null", O_RDWR);
    ::dup2(null_fd, STDIN_FILENO);
    ::dup2(null_fd, STDOUT_FILENO);
    ::dup2(log_fd, STDERR_FILENO);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }

  m_server_pid = pid;
  ::close(write_fd);
  const int number = read_display_number(read_fd);
  ::close(read_fd);
  if (number < 0) {
    stop_xvfb();
    const std::string message = last_line(log.get());
    fail("cannot start Xvfb ({}): {}", xvfb,
         message.empty() ? "it reported no display number" : message);
  }
  m_display = ":" + std::to_string(number);
  if (!display_answers(m_display)) {
    stop_xvfb();
    fail("Xvfb started on display {} but does not accept connections", m_display);
  }
}

void OffscreenDisplay::stop_xvfb()
{
  if (m_server_pid <= 0)
    return;
  ::kill(m_server_pid, SIGTERM);
  const auto deadline = Clock::now() + kStopTimeout;
  bool reaped = false;
  while (!reaped && Clock::now() < deadline) {
    const pid_t done = ::waitpid(m_server_pid, nullptr, WNOHANG);
    if (done == m_server_pid || (done < 0 && errno != EINTR))
      reaped = true;
    else
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (!reaped) {
    ::kill(m_server_pid, SIGKILL);
    while (::waitpid(m_server_pid, nullptr, 0) < 0 && errno == EINTR) {
    }
  }
  m_server_pid = 0;
}

} // namespace ligsim::render
