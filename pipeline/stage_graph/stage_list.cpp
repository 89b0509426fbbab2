#include "pipeline/stage_graph/stage_files.hpp"
#include "pipeline/stage_graph/stage_graph.hpp"

namespace ligsim::pipeline {

namespace fs = std::filesystem;

namespace {

std::vector<fs::path> ligament_only(const BuildConfig& c)
{
  return {c.surface};
}

std::vector<fs::path> ligament_and_bones(const BuildConfig& c)
{
  std::vector<fs::path> inputs{c.surface};
  for (const fs::path& bone : {c.femur, c.tibia})
    if (!bone.empty())
      inputs.push_back(bone);
  return inputs;
}

std::vector<fs::path> none(const BuildConfig&)
{
  return {};
}

/// The files the anatomy reads: landmark surfaces, the bones and the further parts it is read
/// off.
std::vector<fs::path> anatomy_inputs(const BuildConfig& c)
{
  if (c.anatomy.known)
    return {}; // found by the knee's build, and part of the stage's parameters
  std::vector<fs::path> inputs;
  for (const std::string& surface :
       {c.anatomy.medial_epicondyle_surface, c.anatomy.lateral_epicondyle_surface})
    if (!surface.empty())
      inputs.emplace_back(surface);
  for (const fs::path& bone : {c.femur, c.tibia})
    if (!bone.empty())
      inputs.push_back(bone);
  for (const auto& [name, file] : c.anatomy.parts)
    inputs.push_back(file);
  return inputs;
}

/// The ligament, the bones and the footprint patches.
std::vector<fs::path> attachment_inputs(const BuildConfig& c)
{
  std::vector<fs::path> inputs = ligament_and_bones(c);
  for (const std::string& patch : {c.femur_attachment.patch, c.tibia_attachment.patch})
    if (!patch.empty())
      inputs.emplace_back(patch);
  return inputs;
}

} // namespace

const std::vector<Stage>& build_stages()
{
  static const std::vector<Stage> stages = {
      {"anatomy",
       "the knee's side, anatomical directions and landmarks",
       {},
       {files::anatomy},
       anatomy_inputs,
       run_anatomy},
      {"attachments",
       "attachment footprints A1 (femur) and A2 (tibia) on the ligament surface",
       {"anatomy"},
       {files::attachments},
       attachment_inputs,
       run_attachments},
      {"voxelize",
       "inside/outside voxel image of the ligament",
       {},
       {files::mask, files::mask_vdb},
       ligament_only,
       run_voxelize},
      {"distance",
       "distance of every voxel to the surface (from the voxelize stage's level set)",
       {"voxelize"},
       {files::distance, files::distance_vdb},
       ligament_only,
       run_distance},
      {"centerline",
       "minimal-cost path between the attachment areas (eq. 25)",
       {"attachments", "voxelize", "distance"},
       {files::centerline},
       ligament_only,
       run_centerline},
      {"field",
       "diffusion field D, 0 on the centerline and 1 on the boundary",
       {"voxelize", "centerline"},
       {files::field, files::field_vdb},
       ligament_only,
       run_field},
      {"tetmesh",
       "tetrahedral mesh (CGAL Mesh_3) with the footprints' rims as edges",
       {"attachments"},
       {files::mesh},
       ligament_only,
       run_tetmesh},
      {"fibers",
       "fiber direction per tet",
       {"voxelize", "centerline", "field", "tetmesh"},
       {files::fibers, files::fiber_lines},
       none,
       run_fibers},
      {"model",
       "simulation model: fibers with in-situ strain, bone-bound nodes, scene",
       {"attachments", "fibers"},
       {files::model, files::scene},
       ligament_and_bones,
       run_model},
  };
  return stages;
}

} // namespace ligsim::pipeline
