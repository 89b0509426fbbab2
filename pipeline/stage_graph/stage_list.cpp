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

} // namespace

const std::vector<Stage>& build_stages()
{
  static const std::vector<Stage> stages = {
      {"attachments",
       "attachment areas A1 (femur) and A2 (tibia) on the ligament surface",
       {},
       {files::attachments},
       ligament_and_bones,
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
      {"tetmesh", "tetrahedral mesh (CGAL Mesh_3)", {}, {files::mesh}, ligament_only, run_tetmesh},
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
