#pragma once
/// @brief `--set TABLE.KEY=VALUE` on the command line: any key of a TOML config, set over the
/// file's value before the config's reader reads it. The readers' checks (type, range, unknown
/// keys) then apply to it as to the file, and their messages name the `--set` it came from.

#include <toml++/toml.h>

#include <string>
#include <vector>

namespace ligsim {

/// Sets each "a.b.key=VALUE" into `root`. VALUE is TOML (1.2, true, [0, 1, 0], "text"); a
/// word that is not TOML is taken as text (--set centerline.span=attachments). Over an array of
/// tables ([[ligament]]) the setting applies to every table of it. InputError naming the
/// assignment when it is not of that form.
void apply_overrides(toml::table& root, const std::vector<std::string>& assignments);

/// "key=VALUE" with VALUE written as TOML, exactly (a double round-trips): what a convenience
/// flag sets, as `--set` would (--cell-size 1.2 is tetmesh.cell_size_mm=1.2), so that it meets
/// the config reader's checks.
std::string toml_assignment(const std::string& key, double value);
std::string toml_assignment(const std::string& key, int value);
std::string toml_assignment(const std::string& key, bool value);
std::string toml_assignment(const std::string& key, const std::string& text);
std::string toml_assignment(const std::string& key, const std::vector<double>& values);
std::string toml_assignment(const std::string& key, const std::vector<int>& values);
std::string toml_assignment(const std::string& key, const std::vector<std::string>& values);

/// What a `--set` on the command line is for, for the commands' help.
inline constexpr const char* kSetHelp =
    "set a config key over the file, TABLE.KEY=VALUE (repeatable; any key of the config, e.g. "
    "tetmesh.cell_size_mm=1.2; over [[ligament]] tables it sets every ligament)";

} // namespace ligsim
