#include "stages/io/metaimage_check.hpp"

#include "common/error.hpp"
#include "stages/io/text_cursor.hpp"

#include <algorithm>
#include <cstddef>
#include <string>

namespace ligsim::io {

namespace {

std::string trimmed(const std::string& text)
{
  const std::size_t begin = text.find_first_not_of(" \t\r");
  if (begin == std::string::npos)
    return "";
  return text.substr(begin, text.find_last_not_of(" \t\r") - begin + 1);
}

} // namespace

void check_metaimage_header(const std::filesystem::path& file)
{
  const std::string bytes = read_bytes(file);
  std::size_t line = 1;
  for (std::size_t begin = 0; begin < bytes.size(); ++line) {
    const std::size_t end = std::min(bytes.find('\n', begin), bytes.size());
    const std::string text = bytes.substr(begin, end - begin);
    begin = end + 1;
    const std::size_t equals = text.find('=');
    if (equals == std::string::npos)
      continue;
    const std::string key = trimmed(text.substr(0, equals));
    if (key == "ElementDataFile")
      return; // the data follow (for .mha, in this file)
    if (key != "NDims")
      continue;
    const std::string value = trimmed(text.substr(equals + 1));
    const bool whole_1_to_10 =
        value == "10" || (value.size() == 1 && value[0] >= '1' && value[0] <= '9');
    if (!whole_1_to_10)
      fail("'{}' line {}: NDims = '{:.40}': expected a whole number from 1 to 10", file.string(),
           line, value);
  }
}

} // namespace ligsim::io
