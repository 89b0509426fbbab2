#include "pipeline/stage_graph/label_inputs.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/joined_names.hpp"
#include "common/progress.hpp"
#include "common/vtk_files.hpp"
#include "pipeline/stage_graph/stage_files.hpp"
#include "stages/anatomy/part_names.hpp"
#include "stages/io/vtk_convert.hpp"
#include "stages/labelmap/label_surface.hpp"
#include "stages/repair/repair.hpp"

#include <fmt/format.h>
#include <vtkPolyData.h>

#include <optional>
#include <set>
#include <tuple>

namespace ligsim::pipeline {

namespace fs = std::filesystem;

namespace {

nlohmann::json selection_json(const labelmap::Selection& s, const TriangleSurface& surface,
                              const std::vector<labelmap::LabelName>& names)
{
  nlohmann::json known = nlohmann::json::array();
  for (const labelmap::LabelName& n : names)
    if (n.value == s.label)
      known.push_back({{"name", n.name}, {"source", n.source}});
  return {{"label", s.label},
          {"names", known},
          {"voxels", s.voxels},
          {"components", s.components},
          {"dropped_voxels", s.dropped_voxels},
          {"filled_hole_voxels", s.filled_hole_voxels},
          {"contour", s.contour},
          {"surface_triangles", surface.F.rows()}};
}

/// The map's frame and the sources of its names.
nlohmann::json map_json(const fs::path& labels, const labelmap::LabelImage& image,
                        const std::vector<fs::path>& tables)
{
  nlohmann::json table_names = nlohmann::json::array();
  for (const fs::path& table : tables)
    table_names.push_back(table.string());
  return {{"file", labels.string()},
          {"frame", image.frame_from_surfaces
                        ? "LPS as ITK reads the image, but the map was made from surfaces "
                          "(ligsim labelmap): its axes are theirs and say nothing of the anatomy"
                        : "LPS (physical coordinates as ITK reads the image)"},
          {"frame_is_anatomical", !image.frame_from_surfaces},
          {"dims", {image.dims.x(), image.dims.y(), image.dims.z()}},
          {"spacing_mm", {image.spacing_mm.x(), image.spacing_mm.y(), image.spacing_mm.z()}},
          {"origin_mm", {image.origin_mm.x(), image.origin_mm.y(), image.origin_mm.z()}},
          {"segment_names", image.segment_names.size()},
          {"colour_tables", table_names}};
}

/// Refuses a ligament label that is in pieces: its model would be a part of the ligament.
void check_ligament_in_one_piece(const labelmap::Selection& s, const labelmap::LabelImage& image)
{
  const long kept = s.voxels - s.filled_hole_voxels;
  const long labelled = kept + s.dropped_voxels;
  if (static_cast<double>(s.dropped_voxels) <= ligament_stray_share * static_cast<double>(labelled))
    return;
  const Eigen::Vector3d& h = image.spacing_mm;
  fail("label {} is in {} pieces (26-connected voxels): its largest holds {} of its {} voxels "
       "({:.0f} %), and at most {:.0f} % may be dropped as stray voxels. A ligament thinner than "
       "the map's voxels ({:.3g} x {:.3g} x {:.3g} mm) breaks between them: segment it at a "
       "finer spacing (thinner slices), or join its pieces in the label",
       s.label, s.components, kept, labelled,
       100.0 * static_cast<double>(kept) / static_cast<double>(labelled),
       100.0 * ligament_stray_share, h.x(), h.y(), h.z());
}

/// A bone's label, or several joined by '+' ("femur+femoral_cartilage", "2+7+8"): the bone with
/// the cartilage on it, one part whose surface the articular contact meets. The labels' numbers,
/// the bone's first.
std::vector<int> part_labels(const LabelPart& part, const std::vector<labelmap::LabelName>& names)
{
  std::vector<int> labels;
  for (const std::string& piece : joined_names(part.label, fmt::format("label '{}'", part.label)))
    labels.push_back(labelmap::resolve_label(piece, names, "label"));
  if (labels.size() > 1 && !part.bone)
    fail("'{}': only a bone's label joins others ('+'), to take its cartilage", part.label);
  return labels;
}

/// `image` with the voxels of `labels` after the first given the first's value.
labelmap::LabelImage joined(const labelmap::LabelImage& image, const std::vector<int>& labels)
{
  labelmap::LabelImage one = image;
  const std::set<int> others(labels.begin() + 1, labels.end());
  for (std::int32_t& voxel : one.labels)
    if (others.count(voxel))
      voxel = labels.front();
  return one;
}

} // namespace

std::vector<labelmap::LabelName> label_names(const fs::path& labels, const fs::path& colour_table,
                                             const labelmap::LabelImage& image,
                                             std::vector<fs::path>& tables)
{
  std::vector<labelmap::LabelName> names = image.segment_names;
  if (!colour_table.empty()) {
    if (!fs::is_regular_file(colour_table))
      fail("missing colour table '{}'", colour_table.string());
    tables = {colour_table};
  } else {
    std::string note;
    tables = labelmap::colour_tables_found(labels, &note);
    if (!note.empty())
      log_info(note);
  }
  for (const fs::path& table : tables) {
    const std::vector<labelmap::LabelName> more = labelmap::read_colour_table(table);
    names.insert(names.end(), more.begin(), more.end());
  }
  return names;
}

nlohmann::json write_label_surfaces(const fs::path& labels, const fs::path& colour_table,
                                    const std::vector<LabelPart>& parts)
{
  const labelmap::LabelImage image = labelmap::read_label_image(labels);
  std::vector<fs::path> tables;
  const std::vector<labelmap::LabelName> names = label_names(labels, colour_table, image, tables);
  nlohmann::json report = map_json(labels, image, tables);
  std::vector<TriangleSurface> surfaces;
  for (const LabelPart& part : parts) {
    labelmap::Selection selection;
    TriangleSurface surface;
    repair::Report repairs;
    std::vector<int> values;
    try {
      values = part_labels(part, names);
      // A ligament's surface must not cross itself (it is refused if it does); a bone's is
      // repaired into one shell and only ever seen from outside.
      std::optional<labelmap::LabelImage> with_cartilage;
      if (values.size() > 1)
        with_cartilage = joined(image, values);
      surface = labelmap::label_surface(with_cartilage ? *with_cartilage : image, values.front(),
                                        &selection, 30, !part.bone);
      if (!part.bone)
        check_ligament_in_one_piece(selection, image);
      if (selection.contour != "smoothed")
        log_info(fmt::format("{}: the smoothed surface of label {} crossed itself ({}{} triangle "
                             "pairs); made again as the half level of the blurred mask",
                             part.name, values.front(),
                             selection.crossing_pairs >= 16 ? "at least " : "",
                             selection.crossing_pairs));
      // Voxels joined only by an edge or a corner, and parts thinner than the smoothing keeps,
      // give a bone's surface several shells: contact needs one.
      if (part.bone) {
        repair::Result repaired = repair::repair_bone(surface, "its surface");
        surface = std::move(repaired.surface);
        repairs = std::move(repaired.report);
      }
    } catch (const InputError& e) {
      fail("label map '{}', {}: {}", labels.string(), part.name, e.what());
    }
    nlohmann::json& figures = report[part.name];
    figures = selection_json(selection, surface, names);
    if (values.size() > 1)
      figures["joined_labels"] = std::vector<int>(values.begin() + 1, values.end());
    if (part.bone) {
      const auto count = [&](const char* kind) {
        const repair::Repair* found = repairs.find(kind);
        return found ? found->count : 0;
      };
      figures["dropped_inner_cavities"] = count("inner_cavities");
      figures["dropped_stray_shells"] = count("stray_components");
      figures["shells"] = 1 + count("inner_cavities") + count("stray_components");
      figures["bone_repair"] = repair::to_json(repairs);
    }
    surfaces.push_back(std::move(surface));
  }
  for (std::size_t i = 0; i < parts.size(); ++i) {
    ensure_directory(parts[i].file.parent_path());
    write_vtk(io::to_polydata(surfaces[i]), parts[i].file);
  }
  return report;
}

BuildConfig surfaces_from_labels(const BuildConfig& config, const fs::path& dir,
                                 nlohmann::json& report)
{
  if (config.labels.empty())
    return config;
  if (config.ligament_label.empty())
    fail("--labels needs --ligament-label (or [input] ligament_label)");
  BuildConfig result = config;
  std::vector<LabelPart> parts;
  for (const auto& [name, label, target, file] :
       {std::tuple{"ligament", config.ligament_label, &BuildConfig::surface, ligament_from_labels},
        std::tuple{"femur", config.femur_label, &BuildConfig::femur, files::femur},
        std::tuple{"tibia", config.tibia_label, &BuildConfig::tibia, files::tibia}}) {
    if (label.empty())
      continue;
    parts.push_back({name, label, target != &BuildConfig::surface, dir / file});
    result.*target = dir / file;
  }
  report = write_label_surfaces(config.labels, config.colour_table, parts);
  result.label_frame_anatomical = report["frame_is_anatomical"].get<bool>();
  // The ligament's names say which ligament it is, when they name one ligsim knows.
  std::set<std::string> named;
  for (const nlohmann::json& name : report["ligament"]["names"])
    if (const auto part = anatomy::recognise_part(name["name"].get<std::string>());
        part && anatomy::is_ligament(*part))
      named.insert(anatomy::part_name(*part));
  if (named.size() == 1)
    result.ligament_part = *named.begin();
  return result;
}

KneeConfig knee_surfaces_from_labels(const KneeConfig& knee, const fs::path& dir,
                                     nlohmann::json& report)
{
  if (knee.labels.empty())
    return knee;
  KneeConfig result = knee;
  std::vector<LabelPart> parts;
  for (const auto& [name, label, target] :
       {std::tuple{"femur", knee.femur_label, &KneeConfig::femur},
        std::tuple{"tibia", knee.tibia_label, &KneeConfig::tibia},
        std::tuple{"fibula", knee.fibula_label, &KneeConfig::fibula},
        std::tuple{"patella", knee.patella_label, &KneeConfig::patella}}) {
    if (label.empty())
      continue;
    const fs::path file = dir / fmt::format("labels_{}.vtp", name);
    parts.push_back({name, label, true, file});
    result.*target = file;
  }
  result.shared.femur = result.femur;
  result.shared.tibia = result.tibia;
  for (LigamentConfig& ligament : result.ligaments) {
    const fs::path file = dir / ligament.name / ligament_from_labels;
    parts.push_back({"ligament " + ligament.name, ligament.build.ligament_label, false, file});
    ligament.build.surface = file;
    ligament.build.femur = result.femur;
    ligament.build.tibia = ligament.distal_bone == "fibula" ? result.fibula : result.tibia;
  }
  report = write_label_surfaces(knee.labels, knee.colour_table, parts);
  // The anatomy reads the map's frame, when it is a scanner's.
  result.shared.label_frame_anatomical = report["frame_is_anatomical"].get<bool>();
  for (LigamentConfig& ligament : result.ligaments)
    ligament.build.label_frame_anatomical = result.shared.label_frame_anatomical;
  return result;
}

} // namespace ligsim::pipeline
