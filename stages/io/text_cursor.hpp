#pragma once
/// @brief A cursor over a file's bytes for our own format checks: words, numbers and lines with
/// the line number (or, after binary data, the byte offset) in every error.

#include "common/error.hpp"

#include <cstddef>
#include <filesystem>
#include <string>

namespace ligsim::io {

/// The whole file; InputError if it cannot be read.
std::string read_bytes(const std::filesystem::path& file);

class TextCursor {
public:
  TextCursor(const std::filesystem::path& file, const std::string& bytes)
      : file_(file.string())
      , bytes_(bytes)
  {
  }

  /// Skips white space (newlines included); false at the end of the file.
  bool skip_space();
  /// Skips spaces and tabs; true if the line (or the file) ends here.
  bool at_line_end();
  /// The next white-space separated word; `what` names it in the error at the end of the file.
  std::string word(const char* what);
  /// The next word without moving past it (empty at the end of the file).
  std::string peek_word();
  /// The next word, which must be `keyword` (case-sensitive).
  void expect(const char* keyword);
  /// The next word as a number (any form strtod reads, nan and inf included).
  double number(const char* what);
  /// The next word as an integer in [min, max].
  long long integer(const char* what, long long min, long long max);
  /// The rest of the current line, without the line end (errors still name this line).
  std::string rest_of_line();
  /// Moves past the end of the current line.
  void next_line();
  /// Skips `count` bytes of binary data; fails if the file ends first.
  void skip_bytes(std::size_t count, const char* what);

  std::size_t position() const { return position_; }
  std::size_t size() const { return bytes_.size(); }
  const std::string& bytes() const { return bytes_; }

  /// Throws InputError "'FILE' line N: MESSAGE" (or "byte N" once binary data was skipped).
  template <class... Args>
  [[noreturn]] void fail_here(fmt::format_string<Args...> format, Args&&... args) const
  {
    fail("'{}' {}: {}", file_, where(), fmt::format(format, std::forward<Args>(args)...));
  }

private:
  std::string where() const;

  std::string file_;
  const std::string& bytes_;
  std::size_t position_ = 0;
  std::size_t line_ = 1;
  bool binary_seen_ = false;
};

} // namespace ligsim::io
