#include "pipeline/stage_graph/label_inputs.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/vtk_files.hpp"
#include "pipeline/stage_graph/stage_files.hpp"
#include "stages/io/vtk_convert.hpp"
#include "stages/labelmap/label_surface.hpp"
#include "stages/repair/repair.hpp"

#include <vtkPolyData.h>

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
          {"surface_triangles", surface.F.rows()}};
}

/// The names of the map's labels: its segment names, then those of its colour table (the one
/// the config gives, else every table beside the map); the tables read go to `tables`.
std::vector<labelmap::LabelName> label_names(const BuildConfig& config,
                                             const labelmap::LabelImage& image,
                                             std::vector<fs::path>& tables)
{
  std::vector<labelmap::LabelName> names = image.segment_names;
  if (!config.colour_table.empty()) {
    if (!fs::is_regular_file(config.colour_table))
      fail("missing colour table '{}'", config.colour_table.string());
    tables = {config.colour_table};
  } else {
    for (const fs::path& table : labelmap::colour_tables_beside(config.labels))
      if (fs::is_regular_file(table))
        tables.push_back(table);
  }
  for (const fs::path& table : tables) {
    const std::vector<labelmap::LabelName> more = labelmap::read_colour_table(table);
    names.insert(names.end(), more.begin(), more.end());
  }
  return names;
}

} // namespace

BuildConfig surfaces_from_labels(const BuildConfig& config, const fs::path& dir,
                                 nlohmann::json& report)
{
  if (config.labels.empty())
    return config;
  if (config.ligament_label.empty())
    fail("--labels needs --ligament-label (or [input] ligament_label)");
  const labelmap::LabelImage image = labelmap::read_label_image(config.labels);
  std::vector<fs::path> tables;
  const std::vector<labelmap::LabelName> names = label_names(config, image, tables);

  struct Part {
    const char* name;
    std::string label;
    fs::path BuildConfig::*target;
    const char* file;
  };
  const Part parts[] = {
      {"ligament", config.ligament_label, &BuildConfig::surface, ligament_from_labels},
      {"femur", config.femur_label, &BuildConfig::femur, files::femur},
      {"tibia", config.tibia_label, &BuildConfig::tibia, files::tibia}};
  std::vector<std::pair<const Part*, TriangleSurface>> surfaces;
  nlohmann::json table_names = nlohmann::json::array();
  for (const fs::path& table : tables)
    table_names.push_back(table.string());
  report = {{"file", config.labels.string()},
            {"frame", "LPS (physical coordinates as ITK reads the image)"},
            {"dims", {image.dims.x(), image.dims.y(), image.dims.z()}},
            {"spacing_mm", {image.spacing_mm.x(), image.spacing_mm.y(), image.spacing_mm.z()}},
            {"origin_mm", {image.origin_mm.x(), image.origin_mm.y(), image.origin_mm.z()}},
            {"segment_names", image.segment_names.size()},
            {"colour_tables", table_names}};
  for (const Part& part : parts) {
    if (part.label.empty())
      continue;
    labelmap::Selection selection;
    TriangleSurface surface;
    repair::Report repairs;
    const bool bone = part.target != &BuildConfig::surface;
    try {
      const int label = labelmap::resolve_label(part.label, names, "label");
      surface = labelmap::label_surface(image, label, &selection);
      // Voxels joined only by an edge or a corner, and parts thinner than the smoothing keeps,
      // give a bone's surface several shells: contact needs one.
      if (bone) {
        repair::Result repaired = repair::repair_bone(surface, "its surface");
        surface = std::move(repaired.surface);
        repairs = std::move(repaired.report);
      }
    } catch (const InputError& e) {
      fail("label map '{}', {}: {}", config.labels.string(), part.name, e.what());
    }
    report[part.name] = selection_json(selection, surface, names);
    if (bone) {
      const auto count = [&](const char* kind) {
        const repair::Repair* found = repairs.find(kind);
        return found ? found->count : 0;
      };
      nlohmann::json& figures = report[part.name];
      figures["dropped_inner_cavities"] = count("inner_cavities");
      figures["dropped_stray_shells"] = count("stray_components");
      figures["shells"] = 1 + count("inner_cavities") + count("stray_components");
      figures["bone_repair"] = repair::to_json(repairs);
    }
    surfaces.emplace_back(&part, std::move(surface));
  }

  BuildConfig result = config;
  ensure_directory(dir);
  for (const auto& [part, surface] : surfaces) {
    const fs::path file = dir / part->file;
    write_vtk(io::to_polydata(surface), file);
    result.*(part->target) = file;
  }
  return result;
}

} // namespace ligsim::pipeline
