#include "pipeline/stage_graph/knee_from_labels.hpp"

#include "common/error.hpp"
#include "pipeline/stage_graph/config_fields.hpp"
#include "pipeline/stage_graph/label_inputs.hpp"
#include "pipeline/stage_graph/ligament_defaults.hpp"
#include "stages/anatomy/part_names.hpp"
#include "stages/labelmap/label_image.hpp"

#include <fmt/format.h>

#include <map>
#include <set>

namespace ligsim::pipeline {

namespace fs = std::filesystem;

namespace {

/// One label of the map: its names and what they say it is.
struct Label {
  std::int32_t value = 0;
  std::vector<std::string> names;
  long voxels = 0;
  std::optional<anatomy::KneePart> part;
  std::string taken_for; ///< what the build does with it
};

/// A rule's keys as TOML values, in visit_rule's order.
struct TomlValues {
  std::vector<std::pair<std::string, std::string>>& values;

  void operator()(const char* key, const std::string& v) { add(key, "\"" + v + "\""); }
  void operator()(const char* key, bool v) { add(key, v ? "true" : "false"); }
  void operator()(const char* key, double v) { add(key, fmt::format("{}", v)); }
  void operator()(const char* key, const std::vector<int>& v)
  {
    add(key, fmt::format("[{}]", fmt::join(v, ", ")));
  }
  void operator()(const char* key, const Eigen::Vector3d& v)
  {
    add(key, v.allFinite() ? fmt::format("[{}, {}, {}]", v.x(), v.y(), v.z()) : "");
  }
  void add(const char* key, std::string value) { values.emplace_back(key, std::move(value)); }
};

/// TOML lines of a footprint rule: the keys whose values differ from ligsim's defaults.
std::string rule_text(const attachments::Rule& rule)
{
  std::vector<std::pair<std::string, std::string>> ours, defaults;
  visit_rule(rule, TomlValues{ours});
  const attachments::Rule ligsim_defaults;
  visit_rule(ligsim_defaults, TomlValues{defaults});
  std::string text;
  for (std::size_t i = 0; i < ours.size(); ++i)
    if (ours[i].second != defaults[i].second)
      text += ours[i].first + " = " + ours[i].second + "\n";
  return text;
}

std::string quoted_names(const Label& label)
{
  std::vector<std::string> quoted;
  for (const std::string& name : label.names)
    quoted.push_back("'" + name + "'");
  return quoted.empty() ? "(unnamed)" : fmt::format("{}", fmt::join(quoted, ", "));
}

/// The labels present in the image, with their names and what they are.
std::vector<Label> read_labels(const fs::path& labels, const fs::path& colour_table)
{
  const labelmap::LabelImage image = labelmap::read_label_image(labels);
  std::vector<fs::path> tables;
  const std::vector<labelmap::LabelName> names = label_names(labels, colour_table, image, tables);
  std::map<std::int32_t, long> voxels;
  for (const std::int32_t value : image.labels)
    if (value != 0)
      ++voxels[value];
  std::vector<Label> found;
  for (const auto& [value, count] : voxels) {
    Label label;
    label.value = value;
    label.voxels = count;
    std::set<std::string> seen;
    std::set<anatomy::KneePart> parts;
    for (const labelmap::LabelName& n : names)
      if (n.value == value && seen.insert(n.name).second) {
        label.names.push_back(n.name);
        if (const auto part = anatomy::recognise_part(n.name))
          parts.insert(*part);
      }
    if (parts.size() == 1)
      label.part = *parts.begin();
    found.push_back(label);
  }
  if (std::all_of(found.begin(), found.end(), [](const Label& l) { return l.names.empty(); }))
    fail("label map '{}': none of its labels has a name (no segment names in its header, no "
         "colour table beside it): give a colour table (--colour-table), or a knee config that "
         "names each part's label (docs/knee-model.md)",
         labels.string());
  return found;
}

} // namespace

KneeFromLabels knee_from_labels(const fs::path& labels, const fs::path& colour_table,
                                const fs::path& config_dir)
{
  std::vector<Label> found = read_labels(labels, colour_table);
  // Each bone and each ligament once.
  std::map<anatomy::KneePart, const Label*> by_part;
  for (const Label& label : found) {
    if (!label.part || !(anatomy::is_bone(*label.part) || anatomy::is_ligament(*label.part)))
      continue;
    const auto [at, fresh] = by_part.emplace(*label.part, &label);
    if (!fresh)
      fail("label map '{}': two labels name the {}: {} {} and {} {}; give a knee config that "
           "names the one to use (docs/knee-model.md)",
           labels.string(), anatomy::part_name(*label.part), at->second->value,
           quoted_names(*at->second), label.value, quoted_names(label));
  }
  std::string listed;
  for (const Label& label : found)
    listed += fmt::format("{}{} {}", listed.empty() ? "" : "; ", label.value, quoted_names(label));
  const auto has = [&](anatomy::KneePart part) { return by_part.count(part) > 0; };
  using anatomy::KneePart;
  if (!has(KneePart::femur) && !has(KneePart::tibia) && !has(KneePart::fibula) &&
      !has(KneePart::patella))
    fail("label map '{}': no label names a bone ligsim knows (femur, tibia, fibula, patella); "
         "its labels: {}",
         labels.string(), listed);
  if (!has(KneePart::tibia))
    fail("label map '{}': no label names the tibia, where every ligament's distal footprint "
         "lies (or the fibula's, below it); its labels: {}",
         labels.string(), listed);

  KneeFromLabels result;
  std::vector<KneePart> ligaments;
  for (const KneePart part : {KneePart::mcl, KneePart::lcl, KneePart::acl, KneePart::pcl})
    if (has(part))
      ligaments.push_back(part);
  if (ligaments.empty())
    fail("label map '{}': no label names a ligament ligsim builds (MCL, LCL, ACL, PCL, under "
         "names such as tibial_collateral_ligament or anterior_cruciate_ligament); its labels: {}",
         labels.string(), listed);
  if (!has(KneePart::femur))
    result.notes.push_back("no label names the femur: the femoral footprints are the ligaments' "
                           "proximal ends, and there are no femoral landmarks, no flexion axis "
                           "from the condyles and no contact with the femur");

  // Cartilage joins the bone it covers: the bone's surface is then the cartilage's where the
  // articular contact meets it (docs/flexion.md).
  const std::map<KneePart, KneePart> covers = {{KneePart::femoral_cartilage, KneePart::femur},
                                               {KneePart::tibial_cartilage, KneePart::tibia},
                                               {KneePart::patellar_cartilage, KneePart::patella}};
  std::map<KneePart, std::vector<const Label*>> cartilage_of;
  for (Label& label : found) {
    if (!label.part)
      label.taken_for = label.names.empty() ? "not recognised: no name" : "not recognised";
    else if (anatomy::is_bone(*label.part) || anatomy::is_ligament(*label.part))
      label.taken_for = anatomy::part_name(*label.part);
    else if (covers.count(*label.part) && has(covers.at(*label.part))) {
      const KneePart bone = covers.at(*label.part);
      label.taken_for = fmt::format("{}: joined to the {} as its articular layer",
                                    anatomy::part_name(*label.part), anatomy::part_name(bone));
      cartilage_of[bone].push_back(&label);
    } else if (covers.count(*label.part))
      label.taken_for = fmt::format("not used: {} (no label names the bone it covers)",
                                    anatomy::part_name(*label.part));
    else
      label.taken_for = "not used: " + anatomy::part_name(*label.part) +
                        " (menisci move and deform; fixed to the tibia they are no model of one: "
                        "docs/knee-model.md)";
    result.labels.push_back({{"label", label.value},
                             {"names", label.names},
                             {"voxels", label.voxels},
                             {"taken_for", label.taken_for}});
  }

  // The config text.
  std::error_code error;
  fs::path map_path = fs::relative(fs::absolute(labels), fs::absolute(config_dir), error);
  if (error || map_path.empty())
    map_path = fs::absolute(labels);
  std::string& text = result.config_text;
  text +=
      "# The knee `ligsim build --labels` made from the label map's names. Edit it and rebuild\n"
      "# with `ligsim build --config <this file> --out <folder>`; the keys are in\n"
      "# docs/knee-model.md. What each label was taken for:\n";
  for (const Label& label : found)
    text += fmt::format("#   {} {}: {}\n", label.value, quoted_names(label), label.taken_for);
  for (const std::string& note : result.notes)
    text += "# " + note + "\n";
  text += fmt::format("\n[input]\nlabels = \"{}\"\n", map_path.generic_string());
  if (!colour_table.empty())
    text += fmt::format("colour_table = \"{}\"\n", fs::absolute(colour_table).generic_string());
  for (const auto& [part, key] :
       {std::pair{KneePart::femur, "femur_label"}, std::pair{KneePart::tibia, "tibia_label"},
        std::pair{KneePart::fibula, "fibula_label"}, std::pair{KneePart::patella, "patella_label"}})
    if (has(part)) {
      std::string value = std::to_string(by_part.at(part)->value);
      std::string names = quoted_names(*by_part.at(part));
      for (const Label* cartilage : cartilage_of[part]) {
        value += fmt::format("+{}", cartilage->value);
        names += " + " + quoted_names(*cartilage);
      }
      text += cartilage_of[part].empty() ? fmt::format("{} = {}  # {}\n", key, value, names)
                                         : fmt::format("{} = \"{}\"  # {}\n", key, value, names);
    }
  for (const KneePart part : ligaments) {
    const std::string name = anatomy::part_name(part);
    const LigamentDefaults defaults = *ligament_defaults(name);
    text +=
        fmt::format("\n# {}: {}; {}.\n", name, defaults.material_source, defaults.failure_source);
    text += fmt::format("[[ligament]]\nname = \"{}\"\n[ligament.input]\nlabel = {}  # {}\n", name,
                        by_part.at(part)->value, quoted_names(*by_part.at(part)));
    text += fmt::format("# Footprints: {}.\n", defaults.footprint_source);
    text += "[ligament.attachments.femur]\n" + rule_text(defaults.femur_footprint);
    std::string distal = defaults.distal_bone;
    attachments::Rule distal_rule = defaults.distal_footprint;
    if (distal == "fibula" && !has(KneePart::fibula)) {
      result.notes.push_back(fmt::format("no label names the fibula: the {}'s distal footprint is "
                                         "its distal end on the tibia",
                                         name));
      distal = "tibia";
      distal_rule = attachments::Rule{};
      distal_rule.rule = "end";
      distal_rule.end = "distal";
    }
    text += fmt::format("[ligament.attachments.{}]\n", distal) + rule_text(distal_rule);
  }
  return result;
}

} // namespace ligsim::pipeline
