#include "pipeline/commands/commands.hpp"

#include "common/error.hpp"
#include "common/progress.hpp"
#include "common/resources.hpp"
#include "common/run_summary.hpp"
#include "stages/io/surface_reader.hpp"
#include "stages/labelmap/rasterize.hpp"

#include <CLI/CLI.hpp>

#include <memory>

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

labelmap::LabeledSurface read_part(const std::string& text)
{
  const auto colon = text.rfind(':');
  if (colon == std::string::npos || colon + 1 == text.size())
    fail("--part '{}': give FILE:LABEL (for example mcl.stl:1)", text);
  labelmap::LabeledSurface part;
  try {
    part.label = std::stoi(text.substr(colon + 1));
  } catch (const std::exception&) {
    fail("--part '{}': the label after ':' must be a number", text);
  }
  if (part.label <= 0)
    fail("--part '{}': labels are positive (0 is the background)", text);
  part.surface = io::read_surface(text.substr(0, colon));
  io::orient_outward(part.surface);
  return part;
}

void run_labelmap(const LabelmapOptions& o)
{
  if (o.parts.empty())
    fail("give at least one --part FILE:LABEL");
  if (o.spacing.size() != 3)
    fail("--spacing needs three values (x, y, z in mm)");
  std::vector<labelmap::LabeledSurface> parts;
  for (const std::string& text : o.parts)
    parts.push_back(read_part(text));
  // The image covers the first part (or --around) with a margin: the region a scan would show.
  const TriangleSurface region =
      o.around.empty() ? parts.front().surface : io::read_surface(o.around);
  const Eigen::Vector3d lo =
      region.V.colwise().minCoeff().transpose() - Eigen::Vector3d::Constant(o.margin_mm);
  const Eigen::Vector3d hi =
      region.V.colwise().maxCoeff().transpose() + Eigen::Vector3d::Constant(o.margin_mm);
  const StageMeter meter;
  const labelmap::LabelImage image =
      labelmap::rasterize(parts, lo, hi, Eigen::Vector3d(o.spacing[0], o.spacing[1], o.spacing[2]));
  const fs::path out = o.out;
  labelmap::write_label_image(image, out);

  RunSummary summary("labelmap");
  summary.inputs() = {{"parts", o.parts}, {"around", o.around}};
  summary.parameters() = {{"spacing_mm", o.spacing}, {"margin_mm", o.margin_mm}};
  nlohmann::json counts = nlohmann::json::object();
  for (const auto& part : parts)
    counts[std::to_string(part.label)] =
        std::count(image.labels.begin(), image.labels.end(), part.label);
  summary.add_stage("labelmap", meter,
                    {{"dims", {image.dims.x(), image.dims.y(), image.dims.z()}},
                     {"origin_mm", {image.origin_mm.x(), image.origin_mm.y(), image.origin_mm.z()}},
                     {"voxels_per_label", counts}});
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
  command->add_option("--part", options->parts, "FILE:LABEL, a closed surface and its label")
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
