#include "pipeline/stage_graph/label_inputs.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/vtk_files.hpp"
#include "stages/io/vtk_convert.hpp"
#include "stages/labelmap/label_surface.hpp"

#include <vtkPolyData.h>

#include <cctype>
#include <optional>

namespace ligsim::pipeline {

namespace fs = std::filesystem;

namespace {

nlohmann::json selection_json(const labelmap::Selection& s, const TriangleSurface& surface)
{
  return {{"label", s.label},
          {"voxels", s.voxels},
          {"components", s.components},
          {"dropped_voxels", s.dropped_voxels},
          {"filled_hole_voxels", s.filled_hole_voxels},
          {"surface_triangles", surface.F.rows()}};
}

} // namespace

int parse_label(const std::string& text, const std::string& what)
{
  const bool number = !text.empty() && std::all_of(text.begin(), text.end(), [](unsigned char c) {
    return std::isdigit(c) != 0;
  });
  if (!number)
    fail("{} '{}': give the label's number (names are not read yet)", what, text);
  return std::stoi(text);
}

BuildConfig surfaces_from_labels(const BuildConfig& config, const fs::path& dir,
                                 nlohmann::json& report)
{
  if (config.labels.empty())
    return config;
  if (config.ligament_label.empty())
    fail("--labels needs --ligament-label (or [input] ligament_label)");
  const labelmap::LabelImage image = labelmap::read_label_image(config.labels);

  struct Part {
    const char* name;
    std::string label;
    fs::path BuildConfig::*target;
  };
  const Part parts[] = {{"ligament", config.ligament_label, &BuildConfig::surface},
                        {"femur", config.femur_label, &BuildConfig::femur},
                        {"tibia", config.tibia_label, &BuildConfig::tibia}};
  std::vector<std::pair<const Part*, TriangleSurface>> surfaces;
  report = {{"file", config.labels.string()},
            {"frame", "LPS (physical coordinates as ITK reads the image)"},
            {"dims", {image.dims.x(), image.dims.y(), image.dims.z()}},
            {"spacing_mm", {image.spacing_mm.x(), image.spacing_mm.y(), image.spacing_mm.z()}},
            {"origin_mm", {image.origin_mm.x(), image.origin_mm.y(), image.origin_mm.z()}}};
  for (const Part& part : parts) {
    if (part.label.empty())
      continue;
    const int label = parse_label(part.label, fmt::format("{} label", part.name));
    labelmap::Selection selection;
    TriangleSurface surface;
    try {
      surface = labelmap::label_surface(image, label, &selection);
    } catch (const InputError& e) {
      fail("label map '{}', {}: {}", config.labels.string(), part.name, e.what());
    }
    report[part.name] = selection_json(selection, surface);
    surfaces.emplace_back(&part, std::move(surface));
  }

  BuildConfig result = config;
  ensure_directory(dir);
  for (const auto& [part, surface] : surfaces) {
    const fs::path file = dir / fmt::format("labels_{}.vtp", part->name);
    write_vtk(io::to_polydata(surface), file);
    result.*(part->target) = file;
  }
  return result;
}

} // namespace ligsim::pipeline
