#include "pipeline/commands/key_flags.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace ligsim::cli {

CLI::Option* KeyFlags::add_switch(CLI::App& command, const std::string& flag,
                                  const std::string& help, const std::string& key)
{
  auto on = std::make_shared<bool>(false);
  CLI::Option* option = command.add_flag(flag, *on)->description(with_keys(help, {key}));
  // `--strict=false` is given but off: it sets nothing.
  m_flags.push_back(
      {option, {key}, [on](const std::vector<std::string>& prefixed) {
         return *on ? std::vector<std::string>{toml_assignment(prefixed.front(), true)}
                    : std::vector<std::string>{};
       }});
  return option;
}

std::vector<std::string> KeyFlags::assignments(const std::string& prefix) const
{
  std::vector<std::string> all;
  for (const Flag& flag : m_flags) {
    if (flag.option->count() == 0)
      continue;
    std::vector<std::string> prefixed;
    for (const std::string& key : flag.keys)
      prefixed.push_back(prefix + key);
    for (std::string& assignment : flag.assign(prefixed))
      all.push_back(std::move(assignment));
  }
  return all;
}

std::vector<std::string> KeyFlags::given_under(const std::string& table) const
{
  std::vector<std::string> given;
  for (const Flag& flag : m_flags)
    if (flag.option->count() > 0 &&
        std::any_of(flag.keys.begin(), flag.keys.end(),
                    [&](const std::string& key) { return key.rfind(table, 0) == 0; }))
      given.push_back(flag.option->get_name());
  return given;
}

std::string KeyFlags::with_keys(const std::string& help, const std::vector<std::string>& keys)
{
  const std::string set =
      fmt::format("--set {}", fmt::join(keys, keys.size() == 2 ? " and " : ", "));
  // "... (default 1)" becomes "... (default 1; --set KEY)".
  if (!help.empty() && help.back() == ')')
    return fmt::format("{}; {})", help.substr(0, help.size() - 1), set);
  return fmt::format("{} ({})", help, set);
}

} // namespace ligsim::cli
