#pragma once
/// @brief Command-line flags that are short names for config keys (`--cell-size 1.2` is
/// `--set tetmesh.cell_size_mm=1.2`). Each is declared once, with its keys: that gives the
/// option, its help (which names the keys) and, once parsed, the `--set` assignments of the flags
/// given, which then meet the config reader's checks as the file's values do.

#include "common/toml_overrides.hpp"

#include <CLI/CLI.hpp>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace ligsim::cli {

class KeyFlags {
public:
  /// The assignments of one flag's value to its keys (prefixed), in the keys' order.
  template <class T>
  using Assign = std::function<std::vector<std::string>(const T&, const std::vector<std::string>&)>;

  /// `flag` taking a T, which sets each of `keys` to its value (or, with `assign`, to what that
  /// makes of it). `help` says what the value is; the keys are added to it. The option is
  /// returned for its checks, delimiter and group.
  template <class T>
  CLI::Option* add(CLI::App& command, const std::string& flag, const std::string& help,
                   std::vector<std::string> keys, Assign<T> assign = {})
  {
    auto value = std::make_shared<T>();
    if (!assign)
      assign = [](const T& v, const std::vector<std::string>& prefixed) {
        std::vector<std::string> out;
        for (const std::string& key : prefixed)
          out.push_back(toml_assignment(key, v));
        return out;
      };
    CLI::Option* option = command.add_option(flag, *value, with_keys(help, keys));
    m_flags.push_back({option, std::move(keys),
                       [value, assign](const auto& prefixed) { return assign(*value, prefixed); }});
    return option;
  }

  /// A flag without a value that sets `key` to true (`--flag=false`: nothing).
  CLI::Option* add_switch(CLI::App& command, const std::string& flag, const std::string& help,
                          const std::string& key);

  /// The flags given, as `--set` assignments with every key under `prefix` ("ligament." sets
  /// each ligament's key of a knee config), in the order the flags were declared.
  std::vector<std::string> assignments(const std::string& prefix = "") const;
  /// The flags given that set a key under `table` ("attachments."), by name.
  std::vector<std::string> given_under(const std::string& table) const;

private:
  struct Flag {
    CLI::Option* option;
    std::vector<std::string> keys;
    std::function<std::vector<std::string>(const std::vector<std::string>&)> assign;
  };
  /// "HELP (--set KEY)", "HELP (--set KEY1 and KEY2)", or "HELP (default 1; --set KEY)" where
  /// the help ends in parentheses.
  static std::string with_keys(const std::string& help, const std::vector<std::string>& keys);

  std::vector<Flag> m_flags;
};

} // namespace ligsim::cli
