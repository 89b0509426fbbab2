/// The guide's config-key tables against the TOML readers themselves: every key a table names
/// is accepted by its reader, and every key a reader accepts is in its table. A key is probed by
/// adding `key = 1` to its table of a valid base file: the readers answer an unknown key with
/// "unknown key 'key'", and anything else (success, or an error about the value) means the reader
/// knows it. Candidates for keys nobody documented are the string literals of the readers' source.
/// The build table's literal defaults are checked against the parameters' declarations.
/// Conventions of the tables: docs/development.md, "Documentation that stays true".

#include "common/error.hpp"
#include "pipeline/commands/commands.hpp"
#include "pipeline/reports/config_json.hpp"
#include "pipeline/stage_graph/build_config.hpp"
#include "sim/flexion/flexion_config.hpp"
#include "sim/membrane/scene/scene.hpp"
#include "sim/scene/scene.hpp"

#include <CLI/CLI.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <toml++/toml.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace fs = std::filesystem;

namespace {

const fs::path kSource = LIGSIM_SOURCE_DIR;

/// A key as a path of names from the document's root: tables, then the key ("<name>" stands
/// for any name the user chooses).
using KeyPath = std::vector<std::string>;

std::string joined(const KeyPath& path)
{
  std::string text;
  for (const std::string& part : path)
    text += (text.empty() ? "" : ".") + part;
  return text;
}

std::vector<std::string> split(const std::string& text, char separator)
{
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, separator))
    parts.push_back(part);
  return parts;
}

std::string read_file(const fs::path& file)
{
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// One documented key, and where it is written.
struct DocumentedKey {
  KeyPath path;
  std::string where;        ///< "docs/build.md:123"
  std::string default_text; ///< the row's default cell
};

/// The rows of every table that follows `<!-- config-keys: READER -->` in docs/*.md, by reader.
/// "[a/b] key" stands for "[a] key" and "[b] key".
std::map<std::string, std::vector<DocumentedKey>> documented_keys()
{
  std::map<std::string, std::vector<DocumentedKey>> keys;
  const std::regex marker(R"(<!--\s*config-keys:\s*([a-z]+)\s*-->)");
  const std::regex cell(R"(^\|\s*`(?:\[\[?([^\]]+)\]\]?\s+)?([^`\s]+)`\s*\|)");
  for (const fs::directory_entry& entry : fs::directory_iterator(kSource / "docs")) {
    if (entry.path().extension() != ".md")
      continue;
    std::ifstream in(entry.path());
    std::string line, reader;
    int number = 0;
    bool in_table = false;
    while (std::getline(in, line)) {
      ++number;
      std::smatch match;
      if (std::regex_search(line, match, marker)) {
        reader = match[1];
        in_table = false;
        continue;
      }
      if (reader.empty())
        continue;
      if (line.rfind("|", 0) != 0) {
        if (in_table || !line.empty())
          reader.clear(); // the table has ended (or never started)
        continue;
      }
      in_table = true;
      if (line.find("| key |") == 0 || line.find("| ---") == 0)
        continue;
      const std::string where =
          "docs/" + entry.path().filename().string() + ":" + std::to_string(number);
      if (!std::regex_search(line, match, cell)) {
        ADD_FAILURE() << where << ": a config-key row must start with `[table] key` or `key`";
        continue;
      }
      std::vector<KeyPath> tables = {{}};
      if (match[1].matched)
        for (const std::string& segment : split(match[1], '.')) {
          std::vector<KeyPath> expanded;
          for (const KeyPath& table : tables)
            for (const std::string& name : split(segment, '/')) {
              KeyPath longer = table;
              longer.push_back(name);
              expanded.push_back(longer);
            }
          tables = expanded;
        }
      const std::vector<std::string> cells = split(line, '|');
      const std::string default_text = cells.size() > 3 ? cells[3] : "";
      for (KeyPath path : tables) {
        for (const std::string& part : split(match[2], '.'))
          path.push_back(part);
        keys[reader].push_back({path, where, default_text});
      }
    }
  }
  return keys;
}

/// Whether `documented` (with "<name>" wildcards) names `path`.
bool names(const KeyPath& documented, const KeyPath& path)
{
  if (documented.size() != path.size())
    return false;
  for (std::size_t i = 0; i < path.size(); ++i)
    if (documented[i] != path[i] && documented[i] != "<name>")
      return false;
  return true;
}

/// A reader, the base files it is probed with (each valid, together holding every table and
/// taking every branch that reads keys of its own), and its source files.
struct Reader {
  std::string name;
  std::vector<std::string> bases;
  std::vector<std::string> sources;
  /// Reads TOML text written to `file` in `folder`; throws ligsim::Error on a problem.
  std::function<void(const std::string& text, const fs::path& folder)> read;
};

/// A folder for the probes' files, removed at exit.
struct ScratchFolder {
  fs::path path;
  ScratchFolder()
      : path(fs::temp_directory_path() / ("ligsim_config_keys_" + std::to_string(::getpid())))
  {
    fs::create_directories(path);
    std::ofstream(path / "angles.txt") << "0 10 20\n"; // a per_element fiber file
  }
  ~ScratchFolder()
  {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
};

const fs::path& scratch_folder()
{
  static const ScratchFolder folder;
  return folder.path;
}

void write_text(const fs::path& file, const std::string& text)
{
  std::ofstream out(file);
  out << text;
}

std::vector<Reader> readers()
{
  std::vector<Reader> list;
  list.push_back(
      {"build",
       {R"(
[input]
surface = "mcl.stl"
[anatomy]
[attachments.femur]
[attachments.tibia]
[voxelize]
[centerline]
[field]
[tetmesh]
[fibers]
[model]
[error_estimate]
[material]
[flexion]
)"},
       {"pipeline/stage_graph/build_config.cpp", "pipeline/stage_graph/config_fields.hpp"},
       [](const std::string& text, const fs::path& folder) {
         write_text(folder / "build.toml", text);
         ligsim::pipeline::load_build_config(folder / "build.toml");
       }});
  list.push_back({"flexion",
                  {R"(
model = "model"
angles_deg = [0, 30]
[axis]
[anatomy]
[motion]
[ligament]
[material]
[static]
[interactive]
[contact]
[loads]
[articular]
[free]
)"},
                  {"sim/flexion/flexion_config.cpp", "sim/flexion/flexion_fields.hpp",
                   "sim/material/material_fields.hpp", "sim/solver/newton_fields.hpp",
                   "sim/scene/contact_table.hpp"},
                  [](const std::string& text, const fs::path& folder) {
                    ligsim::sim::FlexionSettings settings;
                    ligsim::sim::parse_flexion_config(text, folder, "flexion.toml", settings);
                  }});
  const std::string scene_sets = R"(
[material]
[fibers]
direction = [0, 0, 1]
[node_sets]
bottom = { plane = { axis = "z", at_mm = 0.0 } }
top = { box = { min_mm = [-1, -1, 0.9], max_mm = [2, 2, 1.1] } }
corner = { nodes = [0] }
[[fix]]
set = "bottom"
[[displace]]
set = "top"
displacement_mm = { z = 0.01 }
[[rigid]]
set = "corner"
[[force]]
set = "top"
per_node_n = [0, 0, 0.01]
[output]
[contact]
[[contact.bone]]
name = "bone"
surface = "bone.stl"
follows = "corner"
)";
  list.push_back(
      {"scene",
       {"title = \"t\"\n[mesh]\ngenerator = \"cube\"\ncells = 1\n[solver]\n" + scene_sets,
        "[mesh]\ngenerator = \"box\"\ncells = [1, 1, 1]\nsize_mm = [1, 1, 1]\n"
        "[solver]\nkind = \"dynamic\"\n[dynamics]\n" +
            scene_sets,
        // The bent bar's ends are not on coordinate planes: its sets are node lists.
        std::regex_replace(
            "[mesh]\ngenerator = \"bent_bar\"\ncells = [2, 1, 1]\nsize_mm = [2, 1, 1]\n"
            "bend_deg = 10\n[solver]\n" +
                scene_sets,
            std::regex(R"(\{ (plane|box) = .*\} \})"), "{ nodes = [1, 2] }")},
       {"sim/scene/scene_file.cpp", "sim/scene/scene_fields.hpp",
        "sim/material/material_fields.hpp", "sim/solver/newton_fields.hpp",
        "sim/scene/contact_table.hpp"},
       [](const std::string& text, const fs::path& folder) {
         ligsim::sim::parse_scene(text, folder, "scene.toml");
       }});
  const std::string tear_common = R"(
[material]
fiber_modulus_mpa = 6.0
transverse_modulus_mpa = 2.0
fiber_poisson = 0.45
shear_modulus_mpa = 0.7
thickness_mm = 0.1
density_t_per_mm3 = 1e-6
[tearing]
fiber_threshold_mpa = 1.0
transverse_threshold_mpa = 0.1
[solver]
time_step_s = 1e-3
[[cut]]
points_mm = [[0.0, -0.5], [0.0, 0.5]]
)";
  list.push_back({"tear",
                  {R"(
name = "sheet"
description = "a sheet"
[mesh]
shape = "rectangle"
width_mm = 4.0
height_mm = 4.0
element_size_mm = 0.5
[fibers]
kind = "uniform"
angle_deg = 45.0
[run]
[[fixed]]
box_mm = [-2.01, -2.01, -1.99, 2.01]
[[traction]]
box_mm = [1.99, -2.01, 2.01, 2.01]
direction = [1.0, 0.0]
rate_n_per_mm_per_s = 0.02
max_n_per_mm = 0.2
)" + tear_common,
                   R"(
[mesh]
shape = "disc"
radius_mm = 2.0
element_size_mm = 0.5
[fibers]
kind = "per_element"
path = "angles.txt"
[run]
centre_mm = [0.0, 0.0]
[[fixed]]
outside_radius_mm = 1.9
[grasp]
radius_mm = 0.5
force_rate_n_per_s = 0.002
max_force_n = 0.01
)" + tear_common},
                  {"sim/membrane/scene/scene_file.cpp", "sim/membrane/scene/scene_fields.hpp"},
                  [](const std::string& text, const fs::path& folder) {
                    write_text(folder / "tear.toml", text);
                    ligsim::membrane::load_scene(folder / "tear.toml");
                  }});
  return list;
}

/// The table at `path[from..]` below `table` (arrays of tables: their first table; "<name>": the
/// first entry below which the rest of the path exists); nullptr where there is none.
toml::table* table_at(toml::table& table, const KeyPath& path, std::size_t from = 0)
{
  if (from == path.size())
    return &table;
  const auto below = [&](toml::node* node) -> toml::table* {
    if (node != nullptr && node->is_array_of_tables())
      node = node->as_array()->get(0);
    toml::table* sub = node != nullptr ? node->as_table() : nullptr;
    return sub != nullptr ? table_at(*sub, path, from + 1) : nullptr;
  };
  if (path[from] != "<name>")
    return below(table.get(path[from]));
  for (auto& [key, node] : table)
    if (toml::table* found = below(&node))
      return found;
  return nullptr;
}

/// Every table of `table` and below (arrays of tables by their first table), with its path.
void list_tables(const toml::table& table, const KeyPath& path, std::vector<KeyPath>& out)
{
  out.push_back(path);
  for (const auto& [key, node] : table) {
    KeyPath longer = path;
    longer.emplace_back(key.str());
    if (const toml::table* sub = node.as_table())
      list_tables(*sub, longer, out);
    else if (node.is_array_of_tables())
      list_tables(*node.as_array()->get(0)->as_table(), longer, out);
  }
}

enum class Answer { accepted, unknown, base_failed };

/// Adds `key = 1` to the table at `table_path` of `base` and reads the result; the problem the
/// reader reports goes to `message`.
Answer probe(const Reader& reader, const std::string& base, const KeyPath& table_path,
             const std::string& key, std::string& message)
{
  toml::table document = toml::parse(base);
  toml::table* table = table_at(document, table_path);
  if (table == nullptr)
    return Answer::base_failed;
  table->insert_or_assign(key, 1);
  std::ostringstream text;
  text << document << "\n";
  try {
    reader.read(text.str(), scratch_folder());
  } catch (const ligsim::Error& e) {
    message = e.what();
    if (message.find("unknown key '" + key + "'") != std::string::npos)
      return Answer::unknown;
  }
  return Answer::accepted;
}

/// The quoted identifiers of the reader's source files: every key it can read is among them.
std::set<std::string> literals(const Reader& reader)
{
  std::set<std::string> found;
  const std::regex literal(R"re("([a-z][a-z0-9_]*)")re");
  for (const std::string& source : reader.sources) {
    const std::string text = read_file(kSource / source);
    EXPECT_FALSE(text.empty()) << "cannot read " << source;
    for (auto it = std::sregex_iterator(text.begin(), text.end(), literal);
         it != std::sregex_iterator(); ++it)
      found.insert((*it)[1]);
  }
  return found;
}

class ConfigKeys : public ::testing::TestWithParam<std::string> {
protected:
  const Reader& reader() const
  {
    static const std::vector<Reader> all = readers();
    for (const Reader& r : all)
      if (r.name == GetParam())
        return r;
    throw std::runtime_error("no reader " + GetParam());
  }
  const std::vector<DocumentedKey>& documented() const
  {
    static const std::map<std::string, std::vector<DocumentedKey>> all = documented_keys();
    static const std::vector<DocumentedKey> none;
    const auto found = all.find(GetParam());
    return found == all.end() ? none : found->second;
  }
};

TEST_P(ConfigKeys, BaseFilesAreValid)
{
  for (const std::string& base : reader().bases) {
    try {
      reader().read(base, scratch_folder());
    } catch (const ligsim::Error& e) {
      ADD_FAILURE() << GetParam() << ": a base file of this test is refused: " << e.what() << "\n"
                    << base;
    }
  }
}

TEST_P(ConfigKeys, EveryDocumentedKeyIsAccepted)
{
  ASSERT_FALSE(documented().empty())
      << "no table follows <!-- config-keys: " << GetParam() << " --> in docs/*.md";
  for (const DocumentedKey& key : documented()) {
    const KeyPath table(key.path.begin(), key.path.end() - 1);
    bool tried = false, accepted = false;
    std::string message;
    for (const std::string& base : reader().bases) {
      const Answer answer = probe(reader(), base, table, key.path.back(), message);
      tried = tried || answer != Answer::base_failed;
      accepted = accepted || answer == Answer::accepted;
    }
    EXPECT_TRUE(tried) << key.where << ": `" << joined(key.path) << "`: no base file of "
                       << "tests/docs/config_keys_test.cpp has the table [" << joined(table)
                       << "]: add it there, or fix the table's name";
    if (tried) {
      EXPECT_TRUE(accepted) << key.where << ": the guide documents `" << joined(key.path)
                            << "`, which the " << GetParam() << " reader refuses: " << message;
    }
  }
}

TEST_P(ConfigKeys, EveryAcceptedKeyIsDocumented)
{
  const std::set<std::string> candidates = literals(reader());
  const auto is_documented = [&](const KeyPath& path) {
    for (const DocumentedKey& key : documented()) {
      // A table the guide names keys of counts as documented, too.
      const KeyPath prefix(key.path.begin(),
                           key.path.begin() + std::min(key.path.size(), path.size()));
      if (names(prefix, path))
        return true;
    }
    return false;
  };
  // Tables whose keys are names the user chooses ([node_sets]) are not probed themselves.
  const auto holds_names = [&](const KeyPath& table) {
    KeyPath named = table;
    named.push_back("<name>");
    for (const DocumentedKey& key : documented())
      if (key.path.size() > table.size() &&
          names(KeyPath(key.path.begin(), key.path.begin() + named.size()), named) &&
          key.path[table.size()] == "<name>")
        return true;
    return false;
  };
  std::set<std::string> reported;
  for (const std::string& base : reader().bases) {
    toml::table document = toml::parse(base);
    std::vector<KeyPath> tables;
    list_tables(document, {}, tables);
    for (const KeyPath& table : tables) {
      if (holds_names(table))
        continue;
      for (const auto& [key, node] : *table_at(document, table)) {
        KeyPath path = table;
        path.emplace_back(key.str());
        if (!is_documented(path) && reported.insert(joined(path)).second)
          ADD_FAILURE() << "a base file of the " << GetParam() << " reader sets `" << joined(path)
                        << "`, which no config-key table of docs/*.md names";
      }
      for (const std::string& key : candidates) {
        if (table_at(document, table)->contains(key))
          continue;
        std::string message;
        if (probe(reader(), base, table, key, message) != Answer::accepted)
          continue;
        KeyPath path = table;
        path.push_back(key);
        if (!is_documented(path) && reported.insert(joined(path)).second)
          ADD_FAILURE() << "the " << GetParam() << " reader accepts `" << joined(path)
                        << "`, which no config-key table of docs/*.md names";
      }
    }
  }
}

/// A default cell's value as TOML where it is a literal: a number, true or false, or `word`,
/// alone or before a colon ("0: thickness / 8"); empty otherwise ("none", a description).
std::string literal_default(const std::string& cell)
{
  static const std::regex trimmed(R"(^\s+|\s+$)");
  const std::string text = std::regex_replace(cell.substr(0, cell.find(':')), trimmed, "");
  static const std::regex number(R"(^-?[0-9]+(\.[0-9]+)?(e-?[0-9]+)?$)");
  static const std::regex word(R"(^`([a-z0-9_]+)`$)");
  std::smatch match;
  if (std::regex_match(text, number) || text == "true" || text == "false")
    return text;
  if (std::regex_match(text, match, word))
    return "\"" + match[1].str() + "\"";
  return "";
}

/// Everything a config sets, as JSON, from the same key lists its reader walks.
nlohmann::json parameters_of(const std::string& reader, const std::string& text)
{
  if (reader == "build") {
    write_text(scratch_folder() / "defaults.toml", text);
    return ligsim::pipeline::to_json(
        ligsim::pipeline::load_build_config(scratch_folder() / "defaults.toml"));
  }
  if (reader == "tear") {
    write_text(scratch_folder() / "tear.toml", text);
    return ligsim::reports::to_json(ligsim::membrane::load_scene(scratch_folder() / "tear.toml"));
  }
  if (reader == "scene")
    return ligsim::reports::to_json(ligsim::sim::parse_scene(text, scratch_folder(), "scene.toml"));
  ligsim::sim::FlexionSettings settings;
  ligsim::sim::parse_flexion_config(text, scratch_folder(), "flexion.toml", settings);
  nlohmann::json json = ligsim::reports::to_json(settings);
  json["given"] = settings.given; // what a key set rather than left at its default
  return json;
}

class ConfigKeyDefaults : public ::testing::TestWithParam<std::string> {};

TEST_P(ConfigKeyDefaults, TheGuidesDefaultsAreTheReadersOwn)
{
  // The defaults live once, in the parameters' declarations: a key set to the default the guide
  // gives it must leave the whole config as it was.
  const std::string reader = GetParam();
  std::vector<std::string> bases;
  for (const Reader& r : readers())
    if (r.name == reader)
      bases = r.bases;
  int checked = 0;
  const std::map<std::string, std::vector<DocumentedKey>> documented = documented_keys();
  for (const DocumentedKey& key : documented.at(reader)) {
    const std::string value = literal_default(key.default_text);
    const KeyPath table_path(key.path.begin(), key.path.end() - 1);
    // The first base file that has the key's table (a scene's [dynamics] is in its second).
    std::string base;
    for (const std::string& candidate : bases) {
      toml::table probe = toml::parse(candidate);
      if (table_at(probe, table_path) != nullptr) {
        base = candidate;
        break;
      }
    }
    toml::table document = toml::parse(base);
    toml::table* table = table_at(document, table_path);
    if (value.empty() || table == nullptr)
      continue; // no literal default, or a table the key tests above report
    const nlohmann::json unset = parameters_of(reader, base);
    const toml::table literal = toml::parse("v = " + value);
    table->insert_or_assign(key.path.back(), *literal.get("v"));
    std::ostringstream text;
    text << document << "\n";
    // As text: unset points are NaN, which equals nothing, and null in the text.
    nlohmann::json set = parameters_of(reader, text.str());
    // A key given is recorded as given: that is not a change of its value.
    if (set.contains("given"))
      set["given"] = unset["given"];
    EXPECT_TRUE(set.dump() == unset.dump())
        << key.where << ": the guide gives `" << joined(key.path) << "` the default " << value
        << ", but setting it changes "
        << nlohmann::json::diff(nlohmann::json::parse(unset.dump()),
                                nlohmann::json::parse(set.dump()))
               .dump();
    ++checked;
  }
  const std::map<std::string, int> least = {
      {"build", 40}, {"flexion", 35}, {"scene", 30}, {"tear", 15}};
  EXPECT_GE(checked, least.at(reader))
      << "too few literal defaults found: is the table still parsed?";
}

INSTANTIATE_TEST_SUITE_P(Docs, ConfigKeyDefaults,
                         ::testing::Values("build", "flexion", "scene", "tear"),
                         [](const auto& info) { return info.param; });

/// The keys the help of `ligsim <job>`'s flags names ("(--set tetmesh.cell_size_mm)"), by flag.
std::map<std::string, std::vector<std::string>> keys_named_by_flags(const std::string& job)
{
  CLI::App app;
  ligsim::cli::add_build_commands(app);
  ligsim::cli::add_flexion_command(app);
  std::map<std::string, std::vector<std::string>> named;
  const std::regex set(R"(--set ([a-z0-9_.]+(?:(?:, | and )[a-z0-9_.]+)*)\)$)");
  for (const CLI::Option* option : app.get_subcommand(job)->get_options()) {
    std::smatch match;
    const std::string help = option->get_description();
    if (std::regex_search(help, match, set))
      named[option->get_name()] =
          split(std::regex_replace(match[1].str(), std::regex(", | and "), ","), ',');
  }
  return named;
}

TEST(ConfigKeyFlags, EveryKeyAFlagSetsIsAcceptedByItsReader)
{
  // A flag is a short name for the keys its help names; its declaration is the one place that
  // pairs them. A key renamed in the reader and not there fails here, not on a user's command.
  for (const auto& [job, reader_name, at_least] :
       {std::tuple{"build", "build", 20}, std::tuple{"flexion", "flexion", 9}}) {
    const auto named = keys_named_by_flags(job);
    EXPECT_GE(static_cast<int>(named.size()), at_least)
        << "too few of `ligsim " << job << "`'s flags name their keys: is the help still parsed?";
    Reader reader;
    for (const Reader& r : readers())
      if (r.name == reader_name)
        reader = r;
    for (const auto& [flag, keys] : named)
      for (const std::string& key : keys) {
        const KeyPath path = split(key, '.');
        std::string message;
        const Answer answer = probe(reader, reader.bases.front(),
                                    KeyPath(path.begin(), path.end() - 1), path.back(), message);
        EXPECT_EQ(answer, Answer::accepted)
            << "ligsim " << job << " " << flag << " sets `" << key << "`, which the " << reader_name
            << " reader "
            << (answer == Answer::unknown ? "refuses: " + message : "has no table for");
      }
  }
}

INSTANTIATE_TEST_SUITE_P(Docs, ConfigKeys, ::testing::Values("build", "flexion", "scene", "tear"),
                         [](const auto& info) { return info.param; });

} // namespace
