#pragma once
/// @brief What the build stages share: the names of their files and how to load their inputs.

#include "common/knee_anatomy.hpp"
#include "common/mesh.hpp"
#include "pipeline/stage_graph/build_config.hpp"
#include "stages/geometry/grid.hpp"
#include "stages/geometry/polyline.hpp"
#include "stages/repair/repair.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>

namespace ligsim::pipeline {

/// Output files of the stages, in the output folder.
namespace files {
inline constexpr const char* anatomy = "anatomy.json";
inline constexpr const char* attachments = "attachments.vtp";
inline constexpr const char* mask = "mask.vti";
inline constexpr const char* mask_vdb = "surface.vdb"; ///< the level set, for Houdini/Blender
inline constexpr const char* distance = "distance.vti";
inline constexpr const char* distance_vdb = "distance.vdb";
inline constexpr const char* centerline = "centerline.vtp";
inline constexpr const char* field = "field.vti";
inline constexpr const char* field_vdb = "field.vdb";
inline constexpr const char* mesh = "mesh.vtu";
inline constexpr const char* fibers = "fibers.vtu";
inline constexpr const char* fiber_lines = "fibers.vtp";
inline constexpr const char* model = "model.vtu";
inline constexpr const char* femur = "femur.vtp";
inline constexpr const char* tibia = "tibia.vtp";
inline constexpr const char* scene = "scene.toml";
} // namespace files

/// The ligament surface: read, repaired unless `config.strict` (what was repaired goes to
/// `repairs`; point arrays follow the repair), oriented outward, and required to be a closed
/// manifold without self-intersections.
TriangleSurface load_ligament(const BuildConfig& config,
                              std::map<std::string, Eigen::VectorXd>* arrays = nullptr,
                              repair::Report* repairs = nullptr);

/// A bone surface if the config names one: read and repaired into one closed, outward shell
/// (repair::repair_bone; what was done goes to `repairs`).
std::optional<TriangleSurface> load_bone(const std::filesystem::path& file,
                                         repair::Report* repairs = nullptr);

/// Throws InputError when `ligament` lies farther than a few millimetres from every one of
/// `bones` (name, surface): a ligament joins bones, and one touching none is mislabelled or
/// cut off (the message gives its distance to each).
void require_a_bone_nearby(const std::string& what, const TriangleSurface& ligament,
                           const std::vector<std::pair<std::string, TriangleSurface>>& bones);

/// The voxel images, read from the stages' .vdb files (sparse; the .vti files are for ParaView).
Mask load_mask(const std::filesystem::path& dir);
ScalarGrid load_distance(const std::filesystem::path& dir);
ScalarGrid load_field(const std::filesystem::path& dir);
Polyline load_centerline(const std::filesystem::path& dir);
/// The tets of a .vtu file; of 10-node tets their corners, with all their nodes in `tet10` when
/// given (io::from_unstructured_grid).
TetMesh load_mesh(const std::filesystem::path& file, QuadraticTetrahedra* tet10 = nullptr);

/// The two attachment areas stored by the attachments stage: sorted vertex indices.
struct StoredAttachments {
  std::vector<int> femur;
  std::vector<int> tibia;
};
StoredAttachments load_attachments(const std::filesystem::path& dir);

/// Grid geometry and storage for summary.json.
template <class T> nlohmann::json grid_json(const Grid<T>& grid)
{
  return {{"dims", {grid.dims.x(), grid.dims.y(), grid.dims.z()}},
          {"spacing_mm", grid.spacing},
          {"voxels", grid.voxel_count()},
          {"stored_voxels", grid.brick_count() * Grid<T>::kBrickVoxels},
          {"stored_mib", static_cast<double>(grid.memory_bytes()) / (1024.0 * 1024.0)}};
}

/// What the config and the data say of the knee: side, directions, landmarks.
KneeAnatomy knee_anatomy(const BuildConfig& config);

/// The stages' run functions (see stage_list.cpp for the graph).
nlohmann::json run_anatomy(const BuildConfig& config, const std::filesystem::path& dir);
nlohmann::json run_attachments(const BuildConfig& config, const std::filesystem::path& dir);
nlohmann::json run_voxelize(const BuildConfig& config, const std::filesystem::path& dir);
nlohmann::json run_distance(const BuildConfig& config, const std::filesystem::path& dir);
nlohmann::json run_centerline(const BuildConfig& config, const std::filesystem::path& dir);
nlohmann::json run_field(const BuildConfig& config, const std::filesystem::path& dir);
nlohmann::json run_tetmesh(const BuildConfig& config, const std::filesystem::path& dir);
nlohmann::json run_fibers(const BuildConfig& config, const std::filesystem::path& dir);
nlohmann::json run_model(const BuildConfig& config, const std::filesystem::path& dir);

} // namespace ligsim::pipeline
