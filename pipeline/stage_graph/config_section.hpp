#pragma once
/// @brief Reading one table of a TOML config into parameters, shared by the one-ligament config
/// (build_config.cpp) and the knee config (knee_config.cpp): typed values with the file, line and
/// key in every error, and unknown keys (typos) refused.

#include "common/config_section.hpp"
#include "common/error.hpp"
#include "common/toml_table.hpp"
#include "pipeline/stage_graph/build_config.hpp"
#include "pipeline/stage_graph/config_fields.hpp"

#include <toml++/toml.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace ligsim::pipeline {

namespace config_reading {

namespace fs = std::filesystem;

using Section = ConfigSection;

inline const toml::table* table_at(const toml::table* parent, const char* key)
{
  return parent ? parent->get_as<toml::table>(key) : nullptr;
}

/// A path of the config, relative to the config's folder unless absolute ("" stays "").
inline std::string relative_to(const fs::path& config_file, const std::string& text)
{
  if (text.empty() || fs::path(text).is_absolute())
    return text;
  return (config_file.parent_path() / text).string();
}

/// The stage sections a config table may carry, in data-flow order (besides [input], [anatomy],
/// [attachments] and [material]).
inline const std::vector<std::string>& stage_section_names()
{
  static const std::vector<std::string> names = {
      "voxelize", "centerline", "field", "tetmesh", "fibers", "model", "error_estimate", "flexion"};
  return names;
}

/// Reads the stage sections of `table` over `config` (keys it lacks keep their value); `prefix`
/// goes before the section names in errors ("" or "ligament.").
void read_stage_sections(const toml::table& table, const std::string& prefix, const fs::path& file,
                         BuildConfig& config);

/// Reads [anatomy] of `table` over `config`, landmark surfaces resolved against the file.
void read_anatomy_section(const toml::table& table, const fs::path& file, BuildConfig& config);

/// Reads [<prefix>attachments] of `table` over `config`: `femur`, and the ligament's distal
/// footprint under one of `distal_bones` (into config.tibia_attachment). Returns the distal bone
/// named (the first of `distal_bones` when the table names none). Throws InputError when more
/// than one is given.
std::string read_attachment_sections(const toml::table& table, const std::string& prefix,
                                     const fs::path& file,
                                     const std::vector<std::string>& distal_bones,
                                     BuildConfig& config);

/// Reads [<prefix>material] of `table` over `config`.
void read_material_section(const toml::table& table, const std::string& prefix,
                           const fs::path& file, BuildConfig& config);

/// Parses a TOML file (none: an empty table) with the command line's `--set`s over it; a syntax
/// error is an InputError with the file and line.
toml::table parse_config_file(const fs::path& file, const std::vector<std::string>& overrides = {});

} // namespace config_reading

} // namespace ligsim::pipeline
