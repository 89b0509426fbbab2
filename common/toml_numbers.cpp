#include "common/toml_numbers.hpp"

#include <cstdint>
#include <limits>

namespace ligsim {

std::optional<double> toml_number(const toml::node& node)
{
  if (const toml::value<std::int64_t>* integer = node.as_integer())
    return static_cast<double>(integer->get());
  if (const toml::value<double>* floating = node.as_floating_point())
    return floating->get();
  return std::nullopt;
}

std::optional<int> toml_int(const toml::node& node)
{
  const toml::value<std::int64_t>* integer = node.as_integer();
  if (!integer || integer->get() < std::numeric_limits<int>::min() ||
      integer->get() > std::numeric_limits<int>::max())
    return std::nullopt;
  return static_cast<int>(integer->get());
}

} // namespace ligsim
