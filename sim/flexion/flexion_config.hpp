#pragma once
/// @brief The TOML file of a flexion sweep (every key: docs/flexion.md).

#include "sim/flexion/flexion_settings.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace ligsim::sim {

/// Reads `file` over `settings` (keys not in the file keep their value), with `overrides`
/// ("table.key=value", the command line's --set) over the file; no file: the overrides alone.
/// `model` is relative to the file's folder. Throws InputError naming the file (or the --set),
/// table and key of the first problem, unknown keys included.
void read_flexion_config(const std::filesystem::path& file, FlexionSettings& settings,
                         const std::vector<std::string>& overrides = {});

/// The same from TOML text; `base` resolves relative paths, `name` labels errors.
void parse_flexion_config(const std::string& text, const std::filesystem::path& base,
                          const std::string& name, FlexionSettings& settings);

} // namespace ligsim::sim
