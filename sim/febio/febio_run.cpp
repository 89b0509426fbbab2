#include "sim/febio/febio_run.hpp"

#include "common/error.hpp"
#include "common/resources.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace ligsim::sim {

namespace fs = std::filesystem;

namespace {

/// The last line of `file` that says something, for an error message.
std::string last_words(const fs::path& file)
{
  std::ifstream in(file);
  std::string last;
  for (std::string line; std::getline(in, line);)
    if (line.find_first_not_of(" \t\r") != std::string::npos)
      last = line;
  return last;
}

/// Runs argv with stdout and stderr into `console`; returns the wait status.
int run_process(const std::vector<std::string>& args, const fs::path& directory,
                const fs::path& console)
{
  std::vector<char*> argv;
  for (const std::string& arg : args)
    argv.push_back(const_cast<char*>(arg.c_str()));
  argv.push_back(nullptr);
  const int out_fd = ::open(console.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (out_fd < 0)
    fail("cannot write {}: {}", console.string(), std::strerror(errno));
  const std::string dir = directory.string();
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int error = errno;
    ::close(out_fd);
    fail<SolverError>("cannot start FEBio: fork failed: {}", std::strerror(error));
  }
  if (pid == 0) {
    // FEBio dies with us, even if we are killed and no destructor runs.
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (::getppid() != parent)
      ::_exit(127);
    const int null_fd = ::open("/dev/null", O_RDONLY);
    ::dup2(null_fd, STDIN_FILENO);
    ::dup2(out_fd, STDOUT_FILENO);
    ::dup2(out_fd, STDERR_FILENO);
    if (::chdir(dir.c_str()) != 0)
      ::_exit(126);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  ::close(out_fd);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR)
      fail<SolverError>("waiting for FEBio failed: {}", std::strerror(errno));
  return status;
}

} // namespace

FebioRun run_febio(const fs::path& executable, const fs::path& feb)
{
  const fs::path program = fs::absolute(executable);
  if (!fs::is_regular_file(program) || ::access(program.c_str(), X_OK) != 0)
    fail("--febio {}: not an executable file (FEBio 4's solver, for example "
         "../shared/tools/febio/bin/febio4)",
         executable.string());
  const fs::path input = fs::absolute(feb);
  const fs::path directory = input.parent_path();
  const std::string stem = input.stem().string();
  FebioRun run;
  run.log = directory / (stem + ".log");
  run.console = directory / (stem + ".console.txt");
  fs::remove(run.log); // a log left by an earlier run must not pass for this one's
  const auto start = std::chrono::steady_clock::now();
  const int status = run_process({program.string(), "-i", input.filename().string(), "-o",
                                  stem + ".log", "-p", stem + ".xplt"},
                                 directory, run.console);
  run.wall_s = seconds_since(start);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 127)
    fail<SolverError>("FEBio ({}) could not be started", program.string());
  if (WIFSIGNALED(status))
    fail<SolverError>("FEBio ({}) on {} was killed by signal {} after {:.1f} s (console: {})",
                      program.string(), input.string(), WTERMSIG(status), run.wall_s,
                      run.console.string());
  if (!fs::exists(run.log)) {
    const std::string error = read_febio_log(run.console).error;
    fail<SolverError>("FEBio could not read {}: {} (console: {})", input.string(),
                      error.empty() ? last_words(run.console) : error, run.console.string());
  }
  run.parsed = read_febio_log(run.log);
  if (!run.parsed.normal_termination)
    fail<SolverError>("FEBio did not terminate normally on {}: {} (log: {})", input.string(),
                      run.parsed.error.empty() ? last_words(run.log) : run.parsed.error,
                      run.log.string());
  return run;
}

} // namespace ligsim::sim
