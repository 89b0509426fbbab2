#include "pipeline/commands/commands.hpp"

#include "common/error.hpp"
#include "common/progress.hpp"
#include "common/resources.hpp"
#include "common/run_summary.hpp"
#include "pipeline/stage_graph/label_inputs.hpp"
#include "stages/io/surface_reader.hpp"
#include "stages/labelmap/label_names.hpp"
#include "stages/labelmap/label_surface.hpp"
#include "stages/labelmap/rasterize.hpp"
#include "stages/repair/repair.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cctype>
#include <map>
#include <memory>
#include <tuple>

namespace ligsim::cli {

namespace fs = std::filesystem;

namespace {

struct LabelmapOptions {
  std::vector<std::string> parts; ///< FILE:LABEL
  std::vector<double> spacing{0.3, 0.3, 1.0};
  std::string around;
  double margin_mm = 10.0;
  std::string out;
};

/// A part's surface, label and name (empty if none), and what closing it took.
struct Part {
  labelmap::LabeledSurface labeled;
  std::string name;
  repair::Report repairs;
};

Part read_part(const std::string& text)
{
  const auto is_number = [](const std::string& field) {
    return !field.empty() && std::all_of(field.begin(), field.end(),
                                         [](unsigned char c) { return std::isdigit(c) != 0; });
  };
  // FILE:LABEL or FILE:LABEL:NAME, split from the right (a file name may hold ':').
  const auto split = [](const std::string& s) -> std::pair<std::string, std::string> {
    const auto colon = s.rfind(':');
    if (colon == std::string::npos)
      return {"", s};
    return {s.substr(0, colon), s.substr(colon + 1)};
  };
  Part part;
  auto [file, label_text] = split(text);
  if (!is_number(label_text) && !file.empty()) {
    part.name = label_text;
    std::tie(file, label_text) = split(file);
    if (part.name.empty())
      fail("--part '{}': the name after the label is empty", text);
  }
  if (file.empty() || !is_number(label_text))
    fail("--part '{}': give FILE:LABEL or FILE:LABEL:NAME (for example mcl.stl:1:MCL), the "
         "label a positive number",
         text);
  try {
    part.labeled.label = std::stoi(label_text);
  } catch (const std::exception&) {
    fail("--part '{}': the label {} is too large", text, label_text);
  }
  if (part.labeled.label <= 0)
    fail("--part '{}': labels are positive (0 is the background)", text);
  // Voxels are inside by ray parity, which an open surface breaks (a column through a hole
  // leaks): each part is made one closed shell first, as the build makes a bone.
  repair::Result closed =
      repair::repair_bone(io::read_surface(file), fmt::format("--part '{}'", file));
  for (const std::string& line : repair::describe(closed.report))
    log_info(fmt::format("--part {}: {}", file, line));
  part.labeled.surface = std::move(closed.surface);
  part.repairs = std::move(closed.report);
  return part;
}

/// Each part's 26-connected pieces in the map, as {"pieces", "largest_share"}; a part whose
/// pieces other than the largest hold more than a ligament may drop is said on stderr, since
/// `ligsim build` refuses a ligament in pieces (a part thinner than the voxels breaks between
/// them).
nlohmann::json pieces_per_label(const labelmap::LabelImage& image,
                                const std::vector<labelmap::LabelName>& names,
                                const std::map<int, long>& voxels_per_label,
                                const Eigen::Vector3d& spacing)
{
  nlohmann::json pieces = nlohmann::json::object();
  for (const auto& [label, voxels] : voxels_per_label) {
    if (voxels == 0)
      continue; // covered by later parts
    const labelmap::Selection s = labelmap::label_pieces(image, label);
    const double kept = static_cast<double>(s.voxels - s.filled_hole_voxels);
    const double share = kept / (kept + static_cast<double>(s.dropped_voxels));
    pieces[std::to_string(label)] = {{"pieces", s.components}, {"largest_share", share}};
    if (1.0 - share <= pipeline::ligament_stray_share)
      continue;
    std::string name;
    for (const labelmap::LabelName& n : names)
      if (n.value == label)
        name = fmt::format(" '{}'", n.name);
    log_info(fmt::format("warning: label {}{} is in {} pieces at {:.3g} x {:.3g} x {:.3g} mm, its "
                         "largest {:.0f} % of its voxels: `ligsim build` refuses a ligament in "
                         "pieces; a finer --spacing (thinner slices) keeps a thin part whole",
                         label, name, s.components, spacing.x(), spacing.y(), spacing.z(),
                         100.0 * share));
  }
  return pieces;
}

/// Where the colour table of a label map goes: beside it, same stem, .ctbl.
fs::path colour_table_of(const fs::path& image)
{
  return labelmap::colour_tables_beside(image).front();
}

void run_labelmap(const LabelmapOptions& o)
{
  if (o.parts.empty())
    fail("give at least one --part FILE:LABEL");
  if (o.spacing.size() != 3)
    fail("--spacing needs three values (x, y, z in mm)");
  std::vector<labelmap::LabeledSurface> parts;
  std::vector<labelmap::LabelName> names;
  nlohmann::json repairs = nlohmann::json::object();
  for (const std::string& text : o.parts) {
    Part part = read_part(text);
    if (!part.name.empty())
      names.push_back({part.labeled.label, part.name, 0, "--part"});
    repairs[std::to_string(part.labeled.label)] = repair::to_json(part.repairs);
    parts.push_back(std::move(part.labeled));
  }
  // The image covers the first part (or --around) with a margin: the region a scan would show.
  const TriangleSurface region =
      o.around.empty() ? parts.front().surface : io::read_surface(o.around);
  const Eigen::Vector3d lo =
      region.V.colwise().minCoeff().transpose() - Eigen::Vector3d::Constant(o.margin_mm);
  const Eigen::Vector3d hi =
      region.V.colwise().maxCoeff().transpose() + Eigen::Vector3d::Constant(o.margin_mm);
  const StageMeter meter;
  labelmap::LabelImage image =
      labelmap::rasterize(parts, lo, hi, Eigen::Vector3d(o.spacing[0], o.spacing[1], o.spacing[2]));
  std::sort(names.begin(), names.end(),
            [](const auto& a, const auto& b) { return a.value < b.value; });
  image.segment_names = names;
  const fs::path out = o.out;
  if (!out.parent_path().empty())
    fs::create_directories(out.parent_path());
  labelmap::write_label_image(image, out);
  // The names for every format (NRRD also carries them in its header, as Slicer's segments).
  const fs::path table = colour_table_of(out);
  if (!names.empty()) {
    labelmap::write_colour_table(names, table);
    log_info(fmt::format("wrote {}", table.string()));
  }

  RunSummary summary("labelmap");
  summary.inputs() = {{"parts", o.parts}, {"around", o.around}};
  summary.results()["colour_table"] = names.empty() ? "" : table.string();
  summary.parameters() = {{"spacing_mm", o.spacing}, {"margin_mm", o.margin_mm}};
  std::map<int, long> voxel_counts;
  for (const auto& part : parts)
    voxel_counts[part.label] = 0;
  for (std::int32_t voxel : image.labels)
    if (const auto found = voxel_counts.find(voxel); found != voxel_counts.end())
      ++found->second;
  nlohmann::json counts = nlohmann::json::object();
  for (const auto& [label, voxels] : voxel_counts)
    counts[std::to_string(label)] = voxels;
  const Eigen::Vector3d spacing(o.spacing[0], o.spacing[1], o.spacing[2]);
  summary.add_stage("labelmap", meter,
                    {{"dims", {image.dims.x(), image.dims.y(), image.dims.z()}},
                     {"origin_mm", {image.origin_mm.x(), image.origin_mm.y(), image.origin_mm.z()}},
                     {"voxels_per_label", counts},
                     {"pieces_per_label", pieces_per_label(image, names, voxel_counts, spacing)},
                     {"repairs_per_label", repairs}});
  summary.write(out.parent_path().empty() ? fs::path(".") : out.parent_path());
  log_info(fmt::format("wrote {} ({} x {} x {} voxels)", out.string(), image.dims.x(),
                       image.dims.y(), image.dims.z()));
}

} // namespace

void add_labelmap_command(CLI::App& app)
{
  auto* command = app.add_subcommand(
      "labelmap", "voxelize surfaces into a segmentation label map (.nrrd, .nii.gz, .mha)");
  auto options = std::make_shared<LabelmapOptions>();
  command
      ->add_option("--part", options->parts,
                   "FILE:LABEL or FILE:LABEL:NAME, a closed surface, its label and its name "
                   "(FILE may be knee.glb#MESH)")
      ->required();
  command->add_option("--spacing", options->spacing, "voxel size x,y,z in mm (default 0.3,0.3,1)")
      ->delimiter(',')
      ->expected(3);
  command->add_option("--around", options->around,
                      "surface whose bounding box (plus the margin) the image covers "
                      "(default: the first part)");
  command->add_option("--margin", options->margin_mm, "margin around that box, mm (default 10)");
  command->add_option("--out", options->out, "label map file")->required();
  command->callback([options] { run_labelmap(*options); });
}

} // namespace ligsim::cli
