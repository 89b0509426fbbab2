#include "stages/io/text_cursor.hpp"

#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <iterator>

namespace ligsim::io {

std::string read_bytes(const std::filesystem::path& file)
{
  std::ifstream in(file, std::ios::binary);
  if (!in)
    fail("cannot open '{}'", file.string());
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

namespace {

bool is_space(char c)
{
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

} // namespace

bool TextCursor::skip_space()
{
  while (position_ < bytes_.size() && is_space(bytes_[position_])) {
    if (bytes_[position_] == '\n')
      ++line_;
    ++position_;
  }
  return position_ < bytes_.size();
}

bool TextCursor::at_line_end()
{
  while (position_ < bytes_.size() &&
         (bytes_[position_] == ' ' || bytes_[position_] == '\t' || bytes_[position_] == '\r'))
    ++position_;
  return position_ == bytes_.size() || bytes_[position_] == '\n';
}

std::string TextCursor::word(const char* what)
{
  if (!skip_space())
    fail_here("expected {}, but the file ends (truncated?)", what);
  const std::size_t start = position_;
  while (position_ < bytes_.size() && !is_space(bytes_[position_]))
    ++position_;
  return bytes_.substr(start, position_ - start);
}

std::string TextCursor::peek_word()
{
  if (!skip_space())
    return {};
  std::size_t end = position_;
  while (end < bytes_.size() && !is_space(bytes_[end]))
    ++end;
  return bytes_.substr(position_, end - position_);
}

void TextCursor::expect(const char* keyword)
{
  const std::string found = word(keyword);
  if (found != keyword)
    fail_here("expected '{}', found '{:.40}'", keyword, found);
}

double TextCursor::number(const char* what)
{
  const std::string text = word(what);
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || text.empty())
    fail_here("expected {}, found '{:.40}'", what, text);
  return value;
}

long long TextCursor::integer(const char* what, long long min, long long max)
{
  const std::string text = word(what);
  char* end = nullptr;
  errno = 0;
  const long long value = std::strtoll(text.c_str(), &end, 10);
  if (end != text.c_str() + text.size() || text.empty() || errno == ERANGE)
    fail_here("expected {} (an integer), found '{:.40}'", what, text);
  if (value < min || value > max)
    fail_here("{} is {}, outside {}..{}", what, value, min, max);
  return value;
}

std::string TextCursor::rest_of_line()
{
  const std::size_t start = position_;
  while (position_ < bytes_.size() && bytes_[position_] != '\n')
    ++position_;
  std::size_t end = position_;
  if (end > start && bytes_[end - 1] == '\r')
    --end;
  return bytes_.substr(start, end - start);
}

void TextCursor::next_line()
{
  while (position_ < bytes_.size() && bytes_[position_] != '\n')
    ++position_;
  if (position_ < bytes_.size()) {
    ++position_;
    ++line_;
  }
}

void TextCursor::skip_bytes(std::size_t count, const char* what)
{
  if (count > bytes_.size() - position_)
    fail_here("{} needs {} bytes, but the file ends {} bytes later (truncated?)", what, count,
              bytes_.size() - position_);
  position_ += count;
  binary_seen_ = true;
}

std::string TextCursor::where() const
{
  return binary_seen_ ? fmt::format("byte {}", position_) : fmt::format("line {}", line_);
}

} // namespace ligsim::io
