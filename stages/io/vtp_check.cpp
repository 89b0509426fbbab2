#include "stages/io/vtp_check.hpp"

#include "common/error.hpp"
#include "stages/io/text_cursor.hpp"

#include <algorithm>
#include <cctype>
#include <cstddef>
#include <string>

namespace ligsim::io {

namespace {

struct CountAttribute {
  const char* name;
  long long min;
  long long max;
};

constexpr long long max_count = 2147483647; // VTK's readers keep counts in int

/// The whole number in `value`, or -1 if it is not one (digits only, at most 18 of them).
long long whole_number(const std::string& value)
{
  if (value.empty() || value.size() > 18 ||
      !std::all_of(value.begin(), value.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return -1;
  return std::stoll(value);
}

} // namespace

void check_vtp(const std::filesystem::path& file)
{
  const std::string bytes = read_bytes(file);
  // Raw appended data may hold any bytes; the attributes come before it.
  const std::size_t xml_end = std::min(bytes.find("<AppendedData"), bytes.size());
  for (const CountAttribute& attribute : {CountAttribute{"NumberOfComponents", 1, 1024},
                                          CountAttribute{"NumberOfPoints", 0, max_count},
                                          CountAttribute{"NumberOfVerts", 0, max_count},
                                          CountAttribute{"NumberOfLines", 0, max_count},
                                          CountAttribute{"NumberOfStrips", 0, max_count},
                                          CountAttribute{"NumberOfPolys", 0, max_count},
                                          CountAttribute{"NumberOfTuples", 0, max_count}}) {
    const std::string name = attribute.name;
    for (std::size_t at = bytes.find(name); at < xml_end; at = bytes.find(name, at + 1)) {
      // name = "value" or name='value', as XML allows; anything else is not this attribute.
      std::size_t i = at + name.size();
      const auto skip_space = [&] {
        while (i < xml_end && std::isspace(static_cast<unsigned char>(bytes[i])))
          ++i;
      };
      skip_space();
      if (i >= xml_end || bytes[i] != '=')
        continue;
      ++i;
      skip_space();
      if (i >= xml_end || (bytes[i] != '"' && bytes[i] != '\''))
        continue;
      const std::size_t begin = i + 1;
      const std::size_t end = std::min(bytes.find(bytes[i], begin), xml_end);
      const std::string value = bytes.substr(begin, std::min<std::size_t>(end - begin, 40));
      const long long number = whole_number(value);
      if (number < attribute.min || number > attribute.max)
        fail("'{}' line {}: {}=\"{}\": expected a whole number from {} to {}", file.string(),
             1 + std::count(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(at), '\n'),
             attribute.name, value, attribute.min, attribute.max);
    }
  }
}

} // namespace ligsim::io
