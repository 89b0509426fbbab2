/// The stages that start from the surfaces: attachments, voxelize, distance, tetmesh.

#include "pipeline/stage_graph/stage_files.hpp"

#include "common/progress.hpp"
#include "common/vtk_files.hpp"
#include "sim/mesh/curved_boundary.hpp"
#include "sim/mesh/quadratic_tet.hpp"
#include "stages/attachments/attachments.hpp"
#include "stages/attachments/footprint_rim.hpp"
#include "stages/distance/distance.hpp"
#include "stages/geometry/grid_vdb.hpp"
#include "stages/geometry/grid_vti.hpp"
#include "stages/geometry/surface_query.hpp"
#include "stages/io/surface_reader.hpp"
#include "stages/io/vtk_convert.hpp"
#include "stages/tetmesh/tetmesh.hpp"
#include "stages/voxelize/voxelize.hpp"

#include <fmt/format.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>

namespace ligsim::pipeline {

namespace fs = std::filesystem;

namespace {

nlohmann::json area_json(const attachments::Area& area)
{
  return {{"rule", area.rule},
          {"vertices", area.vertices.size()},
          {"mean_mm", {area.mean.x(), area.mean.y(), area.mean.z()}},
          {"area_mm2", area.area_mm2},
          {"extent_mm", area.extent_mm},
          {"corrections", area.corrections}};
}

std::vector<bool> membership(const std::vector<int>& vertices, Eigen::Index count)
{
  std::vector<bool> flags(static_cast<std::size_t>(count), false);
  for (int v : vertices)
    flags[static_cast<std::size_t>(v)] = true;
  return flags;
}

} // namespace

nlohmann::json run_attachments(const BuildConfig& config, const fs::path& dir)
{
  std::map<std::string, Eigen::VectorXd> arrays;
  const TriangleSurface ligament = load_ligament(config, &arrays);
  const auto femur = load_bone(config.femur);
  const auto tibia = load_bone(config.tibia);
  attachments::Inputs inputs;
  inputs.ligament = &ligament;
  inputs.femur = femur ? &*femur : nullptr;
  inputs.tibia = tibia ? &*tibia : nullptr;
  inputs.arrays = std::move(arrays);
  std::optional<TriangleSurface> femur_patch, tibia_patch;
  if (!config.femur_attachment.patch.empty())
    femur_patch = io::read_surface(config.femur_attachment.patch);
  if (!config.tibia_attachment.patch.empty())
    tibia_patch = io::read_surface(config.tibia_attachment.patch);
  inputs.femur_patch = femur_patch ? &*femur_patch : nullptr;
  inputs.tibia_patch = tibia_patch ? &*tibia_patch : nullptr;
  const KneeAnatomy anatomy = read_knee_anatomy(dir);
  inputs.proximal = anatomy.proximal;
  inputs.posterior = anatomy.posterior;
  for (const auto& [name, landmark] : anatomy.landmarks)
    inputs.landmarks[name] = landmark.point_mm;
  const attachments::Attachments found =
      attachments::find(inputs, config.femur_attachment, config.tibia_attachment);
  for (const attachments::Area* area : {&found.femur, &found.tibia})
    for (const std::string& correction : area->corrections)
      log_info(
          fmt::format("{} footprint: {}", area == &found.femur ? "femoral" : "distal", correction));

  auto surface = io::to_polydata(ligament);
  io::add_flags(surface->GetPointData(), "femur_attachment",
                membership(found.femur.vertices, ligament.V.rows()));
  io::add_flags(surface->GetPointData(), "tibia_attachment",
                membership(found.tibia.vertices, ligament.V.rows()));
  write_vtk(surface, dir / files::attachments);
  return {{"surface_vertices", ligament.V.rows()},
          {"surface_triangles", ligament.F.rows()},
          {"femur", area_json(found.femur)},
          {"tibia", area_json(found.tibia)}};
}

nlohmann::json run_voxelize(const BuildConfig& config, const fs::path& dir)
{
  const vdb::LevelSet level_set = voxelize::level_set(load_ligament(config), config.voxelize);
  level_set.write(dir / files::mask_vdb);
  const Mask mask = level_set.inside();
  write_vti(mask, "inside", dir / files::mask);
  const std::size_t inside = inside_count(mask);
  nlohmann::json figures = grid_json(mask);
  figures["inside_voxels"] = inside;
  figures["inside_volume_mm3"] = static_cast<double>(inside) * std::pow(mask.spacing, 3);
  figures["level_set_active_voxels"] = level_set.active_voxels();
  return figures;
}

nlohmann::json run_distance(const BuildConfig& config, const fs::path& dir)
{
  const SurfaceQuery query(load_ligament(config));
  const ScalarGrid distance =
      distance::signed_distance(vdb::LevelSet::read(dir / files::mask_vdb), query);
  vdb::write_grid(distance, "distance", dir / files::distance_vdb);
  write_vti(distance, "distance", dir / files::distance);
  float d_max = distance.background();
  distance.for_each_stored([&](const Eigen::Vector3i&, float d) { d_max = std::max(d_max, d); });
  nlohmann::json figures = grid_json(distance);
  figures["max_inside_distance_mm"] = d_max;
  return figures;
}

nlohmann::json run_tetmesh(const BuildConfig& config, const fs::path& dir)
{
  const TriangleSurface ligament = load_ligament(config);
  const StoredAttachments areas = load_attachments(dir);
  std::vector<FeatureLine> rims;
  nlohmann::json rim_report = "not kept ([tetmesh] footprint_rims = false)";
  if (config.tetmesh.footprint_rims) {
    rim_report = {{"rule", "each footprint's rim is kept as a chain of mesh edges, so that every "
                           "mesh binds the same area"}};
    for (const auto& [bone, area] : {std::pair{"femur", &areas.femur}, {"tibia", &areas.tibia}}) {
      const std::vector<FeatureLine> found = attachments::footprint_rims(ligament, *area);
      double length = 0;
      for (const FeatureLine& rim : found)
        length += attachments::feature_length(rim);
      rim_report[bone] = {{"loops", found.size()}, {"length_mm", length}};
      rims.insert(rims.end(), found.begin(), found.end());
    }
  }
  const tetmesh::Result result = tetmesh::make_tet_mesh(ligament, config.tetmesh, rims);
  const tetmesh::Quality& q = result.quality;
  nlohmann::json report = {
      {"footprint_rims", rim_report},
      {"tets", q.tets},
      {"nodes", q.nodes},
      {"min_dihedral_deg", q.min_dihedral_deg},
      {"max_dihedral_deg", q.max_dihedral_deg},
      {"worst_radius_edge_ratio", q.worst_radius_edge_ratio},
      {"min_volume_mm3", q.min_volume_mm3},
      {"total_volume_mm3", q.total_volume_mm3},
      {"surface_volume_mm3", q.surface_volume_mm3},
      {"max_surface_distance_mm", q.max_surface_distance_mm},
      {"max_facet_circumcentre_distance_mm", q.max_facet_circumcentre_distance_mm},
      {"used",
       {{"cell_size_mm", result.used.cell_size_mm},
        {"facet_size_mm", result.used.facet_size_mm},
        {"facet_distance_mm", result.used.facet_distance_mm},
        {"order", result.used.order}}}};
  if (result.used.order == 1) {
    write_vtk(io::to_unstructured_grid(result.mesh), dir / files::mesh);
    return report;
  }
  QuadraticTetMesh quadratic = sim::promote_to_quadratic(result.mesh);
  const sim::CurvedBoundary curved = sim::curve_boundary_to_surface(quadratic, ligament);
  write_vtk(io::to_unstructured_grid(quadratic), dir / files::mesh);
  report["quadratic"] = {
      {"nodes", quadratic.V.rows()},
      {"boundary_mid_nodes", curved.boundary_mid_nodes},
      {"moved_onto_surface", curved.moved},
      {"moved_part_way", curved.moved_part_way},
      {"left_straight", curved.left_straight},
      {"max_offset_mm", curved.max_offset_mm},
      {"max_gap_to_surface_mm", curved.max_gap_mm},
      {"min_jacobian_ratio", curved.min_jacobian_ratio},
      {"rule", fmt::format("a boundary edge's mid-edge node moves to the nearest point of the "
                           "surface, halved while an element around it would keep less than {} "
                           "of its straight volume density",
                           sim::kMinCurvedJacobianRatio)}};
  return report;
}

} // namespace ligsim::pipeline
