#include "common/atomic_file.hpp"

#include "common/error.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <fstream>
#include <string>
#include <system_error>
#include <unistd.h>

namespace ligsim {

namespace fs = std::filesystem;

namespace {

/// The temporary's name for `target` written by process `pid`: ".<stem>.tmp-<pid><extension>".
std::string temporary_prefix(const fs::path& target)
{
  return fmt::format(".{}.tmp-", target.stem().string());
}

bool process_is_gone(long pid)
{
  return ::kill(static_cast<pid_t>(pid), 0) == -1 && errno == ESRCH;
}

/// Removes the temporaries of `target` left by writers that no longer run: a job killed with
/// SIGKILL has no chance to remove its own, and nothing else would.
void remove_orphaned_temporaries(const fs::path& target)
{
  const std::string prefix = temporary_prefix(target);
  const std::string extension = target.extension().string();
  std::error_code ec;
  fs::directory_iterator entries(target.parent_path().empty() ? "." : target.parent_path(), ec);
  if (ec)
    return; // no folder yet: nothing left over
  for (const fs::directory_entry& entry : entries) {
    const std::string name = entry.path().filename().string();
    if (name.size() <= prefix.size() + extension.size() || name.rfind(prefix, 0) != 0 ||
        name.compare(name.size() - extension.size(), extension.size(), extension) != 0)
      continue;
    const std::string pid =
        name.substr(prefix.size(), name.size() - prefix.size() - extension.size());
    if (pid.size() > 9 ||
        !std::all_of(pid.begin(), pid.end(), [](unsigned char c) { return std::isdigit(c) != 0; }))
      continue;
    if (std::stol(pid) != ::getpid() && process_is_gone(std::stol(pid)))
      fs::remove(entry.path(), ec);
  }
}

} // namespace

AtomicFile::AtomicFile(fs::path target)
    : m_target(std::move(target))
{
  remove_orphaned_temporaries(m_target);
  m_temp = m_target.parent_path() / (temporary_prefix(m_target) + std::to_string(::getpid()) +
                                     m_target.extension().string());
}

AtomicFile::~AtomicFile()
{
  if (!m_committed) {
    std::error_code ignored;
    fs::remove(m_temp, ignored);
  }
}

void AtomicFile::commit()
{
  std::error_code ec;
  if (!fs::exists(m_temp, ec))
    fail("writing '{}' produced no file", m_target.string());
  fs::rename(m_temp, m_target, ec);
  if (ec)
    fail("cannot move '{}' into place: {}", m_target.string(), ec.message());
  m_committed = true;
}

void write_text_atomically(const fs::path& target, std::string_view contents)
{
  AtomicFile file(target);
  {
    std::ofstream out(file.temp_path(), std::ios::binary);
    out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    if (!out)
      fail("cannot write '{}'", target.string());
  }
  file.commit();
}

void ensure_directory(const fs::path& dir)
{
  if (dir.empty())
    return;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    fail("cannot create output folder '{}'{}", dir.string(), ec ? ": " + ec.message() : "");
}

} // namespace ligsim
