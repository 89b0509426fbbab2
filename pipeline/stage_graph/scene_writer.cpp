#include "pipeline/stage_graph/scene_writer.hpp"

#include "common/atomic_file.hpp"

#include <fmt/format.h>

namespace ligsim::pipeline {

void write_scene(const std::filesystem::path& file, const BuildConfig& config,
                 const model::Axis& axis, const std::vector<std::string>& bones)
{
  const MaterialDefaults& m = config.material;
  std::string bone_note = bones.empty() ? "none given" : "";
  for (std::size_t i = 0; i < bones.size(); ++i)
    bone_note += fmt::format("{}{}", i ? ", " : "", bones[i]);
  const std::string text = fmt::format(
      "# Knee flexion of the built ligament model, written by `ligsim build` (model stage).\n"
      "# Run it with: ligsim simulate {} --out <folder>\n"
      "# Bone surfaces beside this file, for pictures: {}.\n"
      "title = \"ligament model: tibia fixed, femur flexed {} degrees\"\n\n"
      "[mesh]\nfile = \"model.vtu\"\n\n"
      "[material]\nmu_mpa = {}\nk_mpa = {}\nvolumetric = \"{}\"\n\n"
      "# The cell array 'fiber' already carries the in-situ strain ({}) in its length.\n"
      "[fibers]\ncell_data = \"fiber\"\nc3_mpa = {}\nc4 = {}\nc5_mpa = {}\nlambda_star = {}\n"
      "convention = \"{}\"\n\n"
      "[node_sets]\ntibia = {{ point_data = \"tibia_attached\" }}\n"
      "femur = {{ point_data = \"femur_attached\" }}\n\n"
      "[[fix]]\nset = \"tibia\"\n\n"
      "# Flexion axis: {}.\n"
      "[[rigid]]\nset = \"femur\"\naxis = [{}, {}, {}]\npoint_mm = [{}, {}, {}]\nangle_deg = {}\n\n"
      "[solver]\nkind = \"static\"\nload_steps = {}\n\n"
      "[output]\nevery = 1\n",
      file.filename().string(), bone_note, config.flexion.max_angle_deg, m.mu_mpa,
      m.bulk_modulus_mpa, m.volumetric, config.model.in_situ_strain, m.c3_mpa, m.c4, m.c5_mpa,
      m.lambda_star, m.fiber_convention,
      config.flexion.axis_given ? "given in the build config"
                                : "through the femoral attachment along the ligament's thinnest "
                                  "principal direction",
      axis.direction.x(), axis.direction.y(), axis.direction.z(), axis.point.x(), axis.point.y(),
      axis.point.z(), config.flexion.max_angle_deg, config.flexion.steps);
  write_text_atomically(file, text);
}

} // namespace ligsim::pipeline
