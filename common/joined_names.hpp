#pragma once
/// @brief Several parts named as one, joined by '+' ("femur+femoral_cartilage", an atlas' bone in
/// meshes): the one way a config names a part made of pieces.

#include "common/error.hpp"

#include <algorithm>
#include <string>
#include <vector>

namespace ligsim {

/// The names in `text`, in order (one when it has no '+'). Throws InputError naming `what` (how
/// the caller names `text` to the user) when a name between '+' signs is empty.
inline std::vector<std::string> joined_names(const std::string& text, const std::string& what)
{
  std::vector<std::string> names;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find('+', start), text.size());
    names.push_back(text.substr(start, end - start));
    if (names.back().empty())
      fail("{}: an empty name between '+' signs", what);
    start = end + 1;
  }
  return names;
}

} // namespace ligsim
