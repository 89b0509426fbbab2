#pragma once
/// @brief An enumerated parameter of a config, spelled as text in the TOML file and in
/// summary.json: the value, the text of each value, and the values a config may name. The
/// parameter lists (the visit_* functions of the configs) hand it to their readers and writers.

#include <optional>
#include <string>
#include <type_traits>
#include <vector>

namespace ligsim {

template <class E> struct Choice {
  using Value = std::remove_const_t<E>;
  E& value;
  std::string (*name)(Value);
  std::vector<Value> values;

  /// The value whose text is `text`, if any.
  std::optional<Value> parse(const std::string& text) const
  {
    for (const Value& v : values)
      if (name(v) == text)
        return v;
    return std::nullopt;
  }

  /// What a config may write: "\"a\", \"b\" or \"c\"".
  std::string expected() const
  {
    std::string text;
    for (std::size_t i = 0; i < values.size(); ++i)
      text += (i == 0                   ? ""
               : i + 1 == values.size() ? " or "
                                        : ", ") +
              ("\"" + name(values[i]) + "\"");
    return text;
  }
};

template <class E>
Choice<E> choice(E& value, std::string (*name)(std::remove_const_t<E>),
                 std::vector<std::remove_const_t<E>> values)
{
  return {value, name, std::move(values)};
}

} // namespace ligsim
