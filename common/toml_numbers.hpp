#pragma once
/// @brief Numbers out of TOML nodes, the same way in every reader of our TOML files (scenes,
/// build configs, flexion configs, membrane scenes).

#include <toml++/toml.h>

#include <optional>

namespace ligsim {

/// A TOML integer or float as a double; nullopt for anything else. toml++'s value<double>()
/// gives nothing for an integer beyond 2^53 (not exact in a double), which readers then called
/// "not a number"; here it is its nearest double, as `5e17` written as an integer means.
std::optional<double> toml_number(const toml::node& node);

/// A TOML integer that fits an int; nullopt for a float, any other type or an integer out of
/// int's range (which a cast would wrap).
std::optional<int> toml_int(const toml::node& node);

} // namespace ligsim
