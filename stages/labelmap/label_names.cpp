#include "stages/labelmap/label_names.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <fstream>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <sstream>

namespace ligsim::labelmap {

namespace fs = std::filesystem;

namespace {

std::optional<std::int32_t> integer(const std::string& text)
{
  std::int32_t value = 0;
  const char* end = text.data() + text.size();
  const auto [last, error] = std::from_chars(text.data(), end, value);
  if (text.empty() || error != std::errc() || last != end)
    return std::nullopt;
  return value;
}

std::string lower(std::string text)
{
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

/// "1 (segment 0 of seg.nrrd), 4 (seg.ctbl:7)"
std::string describe(const std::vector<const LabelName*>& matches)
{
  std::string text;
  for (const LabelName* match : matches)
    text += fmt::format("{}{} ({})", text.empty() ? "" : ", ", match->value, match->source);
  return text;
}

/// At most `shown` names of `names` with their values, sorted by value.
std::string list_names(const std::vector<LabelName>& names, std::size_t shown = 30)
{
  std::map<std::int32_t, std::set<std::string>> by_value;
  for (const LabelName& n : names)
    by_value[n.value].insert(n.name);
  std::string text;
  std::size_t listed = 0, total = 0;
  for (const auto& [value, value_names] : by_value)
    for (const std::string& name : value_names) {
      ++total;
      if (listed < shown) {
        text += fmt::format("{}'{}' ({})", text.empty() ? "" : ", ", name, value);
        ++listed;
      }
    }
  if (total > listed)
    text += fmt::format(" and {} more", total - listed);
  return text;
}

/// A Slicer-like colour for a label value, RGB 0-255 (0 is the background, black).
std::array<int, 3> colour_of(std::int32_t value)
{
  static constexpr std::array<std::array<int, 3>, 8> palette = {{{216, 101, 79},
                                                                 {128, 174, 128},
                                                                 {241, 214, 145},
                                                                 {177, 122, 101},
                                                                 {111, 184, 210},
                                                                 {221, 130, 101},
                                                                 {144, 238, 144},
                                                                 {192, 104, 88}}};
  if (value == 0)
    return {0, 0, 0};
  return palette[static_cast<std::size_t>(std::abs(value - 1)) % palette.size()];
}

} // namespace

std::vector<LabelName> segment_names(const std::vector<std::pair<std::string, std::string>>& keys,
                                     const fs::path& file)
{
  static const std::regex segment_key(R"(Segment(\d+)_(Name|LabelValue|Layer))");
  std::map<int, LabelName> segments;
  std::set<int> named;
  for (const auto& [key, value] : keys) {
    std::smatch match;
    if (!std::regex_match(key, match, segment_key))
      continue;
    const int index = std::stoi(match[1].str());
    LabelName& segment = segments[index];
    if (segment.source.empty()) {
      segment.value = 1; // Slicer's default when a segment has no LabelValue
      segment.source = fmt::format("segment {} of {}", index, file.filename().string());
    }
    const std::string field = match[2].str();
    if (field == "Name") {
      segment.name = value;
      named.insert(index);
      continue;
    }
    const std::optional<std::int32_t> number = integer(value);
    if (!number)
      fail("label map '{}': header key {} is '{}', not an integer", file.string(), key, value);
    (field == "LabelValue" ? segment.value : segment.layer) = *number;
  }
  std::vector<LabelName> result;
  for (const auto& [index, segment] : segments)
    if (named.count(index) && !segment.name.empty())
      result.push_back(segment);
  return result;
}

std::vector<std::pair<std::string, std::string>> segment_keys(const std::vector<LabelName>& names)
{
  std::vector<std::pair<std::string, std::string>> keys = {
      {"Segmentation_MasterRepresentation", "Binary labelmap"},
      {"Segmentation_ContainedRepresentationNames", "Binary labelmap|"}};
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::array<int, 3> rgb = colour_of(names[i].value);
    const std::string prefix = fmt::format("Segment{}_", i);
    keys.emplace_back(prefix + "ID", fmt::format("Segment_{}", names[i].value));
    keys.emplace_back(prefix + "Name", names[i].name);
    keys.emplace_back(prefix + "LabelValue", std::to_string(names[i].value));
    keys.emplace_back(prefix + "Layer", "0");
    keys.emplace_back(prefix + "Color",
                      fmt::format("{} {} {}", rgb[0] / 255.0, rgb[1] / 255.0, rgb[2] / 255.0));
  }
  return keys;
}

std::vector<LabelName> read_colour_table(const fs::path& file)
{
  std::ifstream in(file);
  if (!in)
    fail("cannot read colour table '{}'", file.string());
  std::vector<LabelName> names;
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    const std::string content = line.substr(0, line.find('#'));
    std::istringstream fields(content);
    std::string value_text, name;
    if (!(fields >> value_text))
      continue; // blank or comment
    const std::optional<std::int32_t> value = integer(value_text);
    // ITK-SNAP's label descriptions end in the name, quoted: value r g b a visible mesh "name".
    const auto open_quote = content.find('"'), close_quote = content.rfind('"');
    if (open_quote != std::string::npos && close_quote > open_quote)
      name = content.substr(open_quote + 1, close_quote - open_quote - 1);
    else
      fields >> name;
    if (!value || name.empty())
      fail("colour table '{}', line {}: expected 'value name r g b a' (or ITK-SNAP's 'value r g b "
           "a visible mesh \"name\"'), found '{}'",
           file.string(), number, line);
    names.push_back({*value, name, 0, fmt::format("{}:{}", file.filename().string(), number)});
  }
  return names;
}

void write_colour_table(const std::vector<LabelName>& names, const fs::path& file)
{
  std::string text = fmt::format("# Color table file {}\n# {} values\n", file.filename().string(),
                                 names.size() + 1);
  text += "0 Background 0 0 0 0\n";
  for (const LabelName& n : names) {
    std::string name = n.name;
    std::replace_if(
        name.begin(), name.end(), [](unsigned char c) { return std::isspace(c) != 0; }, '_');
    const std::array<int, 3> rgb = colour_of(n.value);
    text += fmt::format("{} {} {} {} {} 255\n", n.value, name, rgb[0], rgb[1], rgb[2]);
  }
  write_text_atomically(file, text);
}

std::vector<fs::path> colour_tables_beside(const fs::path& image)
{
  const std::string name = image.filename().string();
  const std::string low = lower(name);
  std::vector<std::string> stems;
  for (const char* ending : {".seg.nrrd", ".nrrd", ".nii.gz", ".nii", ".mha", ".mhd"}) {
    const std::string e = ending;
    if (low.size() > e.size() && low.compare(low.size() - e.size(), e.size(), e) == 0)
      stems.push_back(name.substr(0, name.size() - e.size()));
  }
  if (stems.empty())
    stems.push_back(image.stem().string());
  std::vector<fs::path> tables;
  for (const std::string& stem : stems)
    for (const char* ending : {".ctbl", ".txt", "_ColorTable.ctbl"})
      tables.push_back(image.parent_path() / (stem + ending));
  return tables;
}

std::vector<fs::path> colour_tables_found(const fs::path& image, std::string* note)
{
  std::vector<fs::path> found;
  for (const fs::path& table : colour_tables_beside(image))
    if (fs::is_regular_file(table))
      found.push_back(table);
  if (!found.empty())
    return found;
  std::vector<fs::path> in_folder;
  std::error_code error;
  const fs::path folder = image.has_parent_path() ? image.parent_path() : fs::path(".");
  for (const fs::directory_entry& entry : fs::directory_iterator(folder, error))
    if (entry.is_regular_file() && lower(entry.path().extension().string()) == ".ctbl")
      in_folder.push_back(entry.path());
  std::sort(in_folder.begin(), in_folder.end());
  if (in_folder.size() == 1)
    return in_folder;
  if (in_folder.size() > 1 && note != nullptr) {
    *note = "several colour tables lie beside the map, none with its name:";
    for (const fs::path& table : in_folder)
      *note += " " + table.filename().string();
    *note += " (give one with --colour-table)";
  }
  return {};
}

std::int32_t resolve_label(const std::string& text, const std::vector<LabelName>& names,
                           const std::string& what)
{
  if (const std::optional<std::int32_t> number = integer(text))
    return *number;
  for (const bool ignore_case : {false, true}) {
    std::vector<const LabelName*> matches;
    std::set<std::int32_t> values;
    for (const LabelName& n : names)
      if (ignore_case ? lower(n.name) == lower(text) : n.name == text) {
        matches.push_back(&n);
        values.insert(n.value);
      }
    if (values.size() > 1)
      fail("{} '{}' is ambiguous: it names the labels {}; give the number", what, text,
           describe(matches));
    if (values.empty())
      continue;
    for (const LabelName* match : matches)
      if (match->layer != 0)
        fail("{} '{}' is {}, in layer {}: this map has one layer (export the segmentation as "
             "a single-layer label map)",
             what, text, match->source, match->layer);
    return *values.begin();
  }
  if (names.empty())
    fail("{} '{}': the label map names no labels (no segment names in its header, no colour "
         "table beside it): give the label's number, or a colour table",
         what, text);
  fail("{} '{}' is not a label of this map; its names are {}", what, text, list_names(names));
}

} // namespace ligsim::labelmap
