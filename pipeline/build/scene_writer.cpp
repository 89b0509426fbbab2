#include "pipeline/build/scene_writer.hpp"

#include "common/atomic_file.hpp"

#include <fmt/format.h>

namespace ligsim::pipeline {

void write_scene(const std::filesystem::path& file, const BuildConfig& config,
                 const model::Axis& axis, const std::vector<std::string>& bones)
{
  const MaterialDefaults& m = config.material;
  std::string text = fmt::format(
    "# Knee flexion of the built ligament model, written by `ligsim build` (model stage).\n"
    "# Run it with: ligsim simulate {} --out <folder>\n\n"
    "[mesh]\nfile = \"model.vtu\"\nfiber_array = \"fiber\"\n\n"
    "[material]\nmu_mpa = {}\nc3_mpa = {}\nc4 = {}\nc5_mpa = {}\nlambda_star = {}\n"
    "bulk_modulus_mpa = {}\nfiber_convention = \"{}\"\nvolumetric = \"{}\"\n\n"
    "[[node_sets]]\nname = \"tibia\"\narray = \"tibia_attached\"\n\n"
    "[[node_sets]]\nname = \"femur\"\narray = \"femur_attached\"\n\n"
    "[[fixed]]\nset = \"tibia\"\ncomponents = \"xyz\"\n\n"
    "[[rigid_motion]]\nset = \"femur\"\naxis_point_mm = [{}, {}, {}]\n"
    "axis_direction = [{}, {}, {}]\nangle_deg = {}\n\n"
    "[solver]\ntype = \"static\"\nsteps = {}\n",
    file.filename().string(), m.mu_mpa, m.c3_mpa, m.c4, m.c5_mpa, m.lambda_star,
    m.bulk_modulus_mpa, m.fiber_convention, m.volumetric, axis.point.x(), axis.point.y(),
    axis.point.z(), axis.direction.x(), axis.direction.y(), axis.direction.z(),
    config.flexion.max_angle_deg, config.flexion.steps);
  if (!bones.empty()) {
    text += "\n[pictures]\nsurfaces = [";
    for (std::size_t i = 0; i < bones.size(); ++i)
      text += fmt::format("{}\"{}\"", i ? ", " : "", bones[i]);
    text += "]\n";
  }
  write_text_atomically(file, text);
}

} // namespace ligsim::pipeline
