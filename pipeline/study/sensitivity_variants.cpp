#include "pipeline/study/sensitivity_variants.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/vtk_files.hpp"
#include "pipeline/stage_graph/stage_files.hpp"
#include "pipeline/study/convergence_study.hpp"
#include "pipeline/study/surface_variants.hpp"
#include "stages/attachments/attachments.hpp"
#include "stages/io/vtk_convert.hpp"

#include <fmt/format.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>

namespace ligsim::study {

namespace fs = std::filesystem;

namespace {

constexpr const char* kFemurArray = "study_femur_area";
constexpr const char* kTibiaArray = "study_tibia_area";

/// One variant of one ligament's config.
struct Variant {
  std::string factor;
  std::string name;
  std::string description;
  pipeline::BuildConfig config;
};

/// The attachment areas as vertex lists: femoral, then distal (tibia or fibula).
struct Areas {
  std::vector<int> femur, tibia;
};

/// The source's attachment areas as found by the config's rules from the bones alone (no
/// anatomy, no patches: the rules a one-ligament config of `study variant` uses).
Areas source_areas(const pipeline::BuildConfig& config, const TriangleSurface& surface,
                   const std::map<std::string, Eigen::VectorXd>& arrays)
{
  const auto femur = pipeline::load_bone(config.femur);
  const auto tibia = pipeline::load_bone(config.tibia);
  attachments::Inputs inputs;
  inputs.ligament = &surface;
  inputs.femur = femur ? &*femur : nullptr;
  inputs.tibia = tibia ? &*tibia : nullptr;
  inputs.arrays = arrays;
  const attachments::Attachments found =
      attachments::find(inputs, config.femur_attachment, config.tibia_attachment);
  return {found.femur.vertices, found.tibia.vertices};
}

/// The areas a build found: the flags of its attachments.vtp (the ligament's surface as the
/// build read it, so vertex i is vertex i of load_ligament).
Areas built_areas(const fs::path& folder, Eigen::Index vertices)
{
  const fs::path file = folder / pipeline::files::attachments;
  const auto surface = read_vtp(file);
  if (surface->GetNumberOfPoints() != vertices)
    fail("study sensitivity: {} has {} points, the ligament's surface {}", file.string(),
         surface->GetNumberOfPoints(), vertices);
  Areas areas;
  for (const auto& [name, area] :
       {std::pair{"femur_attachment", &areas.femur}, std::pair{"tibia_attachment", &areas.tibia}}) {
    const Eigen::MatrixXd flags = io::get_array(surface->GetPointData(), name);
    for (Eigen::Index v = 0; v < flags.rows(); ++v)
      if (flags(v, 0) != 0.0)
        area->push_back(static_cast<int>(v));
  }
  return areas;
}

/// Writes `surface` with the two areas as point-data flags and points the config at it, with
/// the "array" rule: the variant keeps exactly the areas it is given.
pipeline::BuildConfig with_surface(const pipeline::BuildConfig& source,
                                   const TriangleSurface& surface, const Areas& areas,
                                   const fs::path& folder)
{
  ensure_directory(folder);
  auto polydata = io::to_polydata(surface);
  for (const auto& [name, area] :
       {std::pair{kFemurArray, &areas.femur}, std::pair{kTibiaArray, &areas.tibia}}) {
    Eigen::VectorXd flags = Eigen::VectorXd::Zero(surface.V.rows());
    for (int v : *area)
      flags(v) = 1.0;
    io::add_array(polydata->GetPointData(), name, flags);
  }
  const fs::path file = folder / "surface.vtp";
  write_vtk(polydata, file);
  pipeline::BuildConfig config = source;
  config.surface = file;
  config.femur_attachment = attachments::Rule{};
  config.femur_attachment.rule = "array";
  config.femur_attachment.array = kFemurArray;
  config.tibia_attachment = attachments::Rule{};
  config.tibia_attachment.rule = "array";
  config.tibia_attachment.array = kTibiaArray;
  return config;
}

std::string signed_label(double value, const std::string& unit)
{
  return fmt::format("{}{:g}{}", value > 0 ? "+" : "", value, unit);
}

/// One ligament's baseline and variants; `folder_of` names the folder of a variant's surface.
std::vector<Variant> ligament_variants(const pipeline::BuildConfig& source,
                                       const fs::path& baseline_folder,
                                       const SensitivitySettings& s,
                                       const std::function<fs::path(const std::string&)>& folder_of)
{
  const TriangleSurface surface = pipeline::load_ligament(source);
  const Areas areas = built_areas(baseline_folder, surface.V.rows());
  auto surface_variant = [&](const std::string& factor, const std::string& name,
                             const std::string& description, const TriangleSurface& changed) {
    return Variant{factor, name, description,
                   with_surface(source, changed, areas, folder_of(name))};
  };

  auto wanted = [&](const std::string& factor) {
    return s.factors.empty() ||
           std::find(s.factors.begin(), s.factors.end(), factor) != s.factors.end();
  };
  std::vector<Variant> variants;
  variants.push_back({"baseline", "baseline", "the source segmentation and config", source});
  for (double fraction :
       wanted("offset") ? std::vector<double>{-1.0, -0.5, 0.5, 1.0} : std::vector<double>{}) {
    const double d = fraction * s.offset_mm;
    variants.push_back(surface_variant("surface offset", "offset" + signed_label(d, "mm"),
                                       fmt::format("surface moved {:g} mm along its normals", d),
                                       offset_surface(surface, d)));
  }
  if (wanted("smoothing")) {
    variants.push_back(
        surface_variant("smoothing", "smoothed",
                        fmt::format("Taubin smoothing, {} iterations", s.smoothing_iterations),
                        smooth_surface(surface, s.smoothing_iterations)));
    variants.push_back(surface_variant(
        "smoothing", "roughened", fmt::format("random normal bumps, rms {:g} mm", s.roughness_mm),
        roughen_surface(surface, s.roughness_mm, 4, 12)));
  }
  for (double d : wanted("attachment-size") ? s.attachment_changes_mm : std::vector<double>{}) {
    const std::string name = "areas" + signed_label(d, "mm");
    variants.push_back(Variant{
        "attachment size", name,
        fmt::format("both attachment areas {} by {:g} mm along the surface",
                    d > 0 ? "grown" : "shrunk", std::abs(d)),
        with_surface(source, surface,
                     {grow_area(surface, areas.femur, d), grow_area(surface, areas.tibia, d)},
                     folder_of(name))});
  }
  if (wanted("attachment-rule")) {
    pipeline::BuildConfig config = source;
    config.tibia_attachment = attachments::Rule{};
    config.tibia_attachment.rule = "end";
    config.tibia_attachment.end_length_mm = s.tibia_end_length_mm;
    variants.push_back({"attachment rule", "tibia-end",
                        fmt::format("distal area: the distal {:g} mm of the ligament (end rule)",
                                    s.tibia_end_length_mm),
                        config});
    config = source;
    config.centerline.span = centerline::parse_span("means");
    variants.push_back({"attachment rule", "span-means",
                        "centerline between the areas' means (the paper's rule)", config});
  }
  for (double alpha : wanted("alpha") ? s.alphas : std::vector<double>{}) {
    pipeline::BuildConfig config = source;
    config.centerline.alpha = alpha;
    variants.push_back({"alpha", fmt::format("alpha{:g}", alpha),
                        fmt::format("centerline alpha {:g}", alpha), config});
  }
  return variants;
}

} // namespace

StudyModel pinned_sizes(const StudyModel& model)
{
  StudyModel pinned = model;
  for (pipeline::LigamentConfig& ligament : pinned.config.ligaments) {
    pipeline::BuildConfig& config = ligament.build;
    const double h = ligament_thickness_mm(config);
    auto pin = [](double& value, double fallback) {
      if (value <= 0.0)
        value = fallback;
    };
    pin(config.voxelize.spacing_mm, h / 8.0);
    pin(config.tetmesh.cell_size_mm, h / 2.0);
    pin(config.tetmesh.facet_size_mm, h / 2.0);
    pin(config.tetmesh.facet_distance_mm, h / 20.0);
  }
  return pinned;
}

std::vector<SensitivityVariant> make_variants(const StudyModel& source,
                                              const fs::path& baseline_dir,
                                              const SensitivitySettings& settings,
                                              const fs::path& folders)
{
  // Each ligament's variants (the same names in the same order for every ligament).
  std::vector<std::vector<Variant>> per_ligament;
  for (std::size_t l = 0; l < source.config.ligaments.size(); ++l) {
    const std::string ligament = source.knee ? source.config.ligaments[l].name : "";
    per_ligament.push_back(ligament_variants(
        source.config.ligaments[l].build, ligament_folder(source, l, baseline_dir), settings,
        [&](const std::string& name) {
          return ligament.empty() ? folders / name : folders / name / ligament;
        }));
  }
  std::vector<SensitivityVariant> variants;
  for (std::size_t v = 0; v < per_ligament.front().size(); ++v) {
    const Variant& first = per_ligament.front()[v];
    SensitivityVariant variant{first.factor, first.name, first.description, source};
    for (std::size_t l = 0; l < per_ligament.size(); ++l)
      variant.model.config.ligaments[l].build = per_ligament[l][v].config;
    variants.push_back(variant);
  }
  return variants;
}

fs::path write_surface_variant(const pipeline::BuildConfig& config, const std::string& kind,
                               double amount, const fs::path& folder)
{
  std::map<std::string, Eigen::VectorXd> arrays;
  const TriangleSurface surface = pipeline::load_ligament(config, &arrays);
  Areas areas = source_areas(config, surface, arrays);
  TriangleSurface changed = surface;
  if (kind == "offset")
    changed = offset_surface(surface, amount);
  else if (kind == "smooth")
    changed = smooth_surface(surface, static_cast<int>(std::lround(amount)));
  else if (kind == "rough")
    changed = roughen_surface(surface, amount, 4, 12);
  else if (kind == "areas") {
    areas.femur = grow_area(surface, areas.femur, amount);
    areas.tibia = grow_area(surface, areas.tibia, amount);
  } else
    fail("study variant: unknown kind '{}' (offset, smooth, rough or areas)", kind);
  if (areas.femur.empty() || areas.tibia.empty())
    fail("study variant: shrinking the attachment areas by {:g} mm leaves one empty", -amount);
  return with_surface(config, changed, areas, folder).surface;
}

} // namespace ligsim::study
