#include "common/atomic_file.hpp"

#include "common/error.hpp"

#include <fstream>
#include <system_error>
#include <unistd.h>

namespace ligsim {

namespace fs = std::filesystem;

AtomicFile::AtomicFile(fs::path target)
    : m_target(std::move(target))
{
  const std::string stem = m_target.stem().string();
  const std::string tag = fmt::format(".{}.tmp-{}", stem, ::getpid());
  m_temp = m_target.parent_path() / (tag + m_target.extension().string());
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
