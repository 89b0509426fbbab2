#include "pipeline/stage_graph/scene_writer.hpp"

#include "common/atomic_file.hpp"
#include "sim/material/material_fields.hpp"

#include <fmt/format.h>

namespace ligsim::pipeline {

namespace {

/// One `key = value` line per visited parameter: a scene's table from its key list.
struct TomlLines {
  std::string& text;

  void operator()(const char* key, double value) { text += fmt::format("{} = {}\n", key, value); }
  template <class E> void operator()(const char* key, Choice<E> choice)
  {
    text += fmt::format("{} = \"{}\"\n", key, choice.name(choice.value));
  }
};

} // namespace

void write_scene(const std::filesystem::path& file, const BuildConfig& config,
                 const model::Axis& axis, const std::vector<std::string>& bones)
{
  std::string material, fibers;
  sim::visit_ground_substance(config.material, TomlLines{material});
  sim::visit_fiber_law(*config.material.fiber, TomlLines{fibers});
  std::string bone_note = bones.empty() ? "none given" : "";
  for (std::size_t i = 0; i < bones.size(); ++i)
    bone_note += fmt::format("{}{}", i ? ", " : "", bones[i]);
  const std::string text = fmt::format(
      "# Knee flexion of the built ligament model, written by `ligsim build` (model stage).\n"
      "# Run it with: ligsim simulate {} --out <folder>\n"
      "# Bone surfaces beside this file, for pictures: {}.\n"
      "title = \"ligament model: tibia fixed, femur flexed {} degrees\"\n\n"
      "[mesh]\nfile = \"model.vtu\"\n\n"
      "[material]\n{}\n"
      "# The cell array 'fiber' already carries the in-situ strain ({}) in its length.\n"
      "[fibers]\ncell_data = \"fiber\"\n{}\n"
      "[node_sets]\ntibia = {{ point_data = \"tibia_attached\" }}\n"
      "femur = {{ point_data = \"femur_attached\" }}\n\n"
      "[[fix]]\nset = \"tibia\"\n\n"
      "# Flexion axis: {}.\n"
      "[[rigid]]\nset = \"femur\"\naxis = [{}, {}, {}]\npoint_mm = [{}, {}, {}]\nangle_deg = {}\n\n"
      "[solver]\nkind = \"static\"\nload_steps = {}\n\n"
      "[output]\nevery = 1\n",
      file.filename().string(), bone_note, config.flexion.max_angle_deg, material,
      config.model.in_situ_strain, fibers,
      config.flexion.axis_given ? "given in the build config"
                                : "through the femoral attachment along the ligament's thinnest "
                                  "principal direction",
      axis.direction.x(), axis.direction.y(), axis.direction.z(), axis.point.x(), axis.point.y(),
      axis.point.z(), config.flexion.max_angle_deg, config.flexion.steps);
  write_text_atomically(file, text);
}

} // namespace ligsim::pipeline
