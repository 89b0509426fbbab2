#pragma once
/// @brief Writes that never leave a half file over a good one.

#include <filesystem>
#include <string_view>

namespace ligsim {

/// A temporary sibling of `target` to write into; commit() renames it over the target.
/// If commit() is never called (an exception, an early return) the temporary is removed
/// and the target is untouched. A job killed with SIGKILL leaves its temporary behind (hidden:
/// ".<stem>.tmp-<pid><ext>"); the next write of the same target removes it once that process
/// is gone.
class AtomicFile {
public:
  explicit AtomicFile(std::filesystem::path target);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile();

  /// Where to write. Keeps the target's extension, so format-sniffing writers still work.
  const std::filesystem::path& temp_path() const { return m_temp; }
  const std::filesystem::path& target() const { return m_target; }

  /// Renames the temporary over the target; throws InputError if the temporary is missing.
  void commit();

private:
  std::filesystem::path m_target;
  std::filesystem::path m_temp;
  bool m_committed = false;
};

/// Writes `contents` to `target` atomically.
void write_text_atomically(const std::filesystem::path& target, std::string_view contents);

/// Creates `dir` (and parents) or throws InputError naming it.
void ensure_directory(const std::filesystem::path& dir);

} // namespace ligsim
