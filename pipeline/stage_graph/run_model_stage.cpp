/// The last stage: the simulation model, the bone surfaces and the scene file.

#include "pipeline/stage_graph/scene_writer.hpp"
#include "pipeline/stage_graph/stage_files.hpp"

#include "common/vtk_files.hpp"
#include "sim/mesh/quadratic_tet.hpp"
#include "stages/io/vtk_convert.hpp"
#include "stages/model/model.hpp"

#include <vtkCellData.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <optional>
#include <tuple>

namespace ligsim::pipeline {

namespace fs = std::filesystem;

nlohmann::json run_model(const BuildConfig& config, const fs::path& dir)
{
  const TriangleSurface ligament = load_ligament(config);
  const StoredAttachments areas = load_attachments(dir);
  auto fibers_grid = read_vtu(dir / files::fibers);
  QuadraticTetrahedra tet10; // for 10-node tets: mesh has their corners, over all their nodes
  const TetMesh mesh = io::from_unstructured_grid(fibers_grid, &tet10);
  const Eigen::MatrixX3d directions = io::get_array(fibers_grid->GetCellData(), "fiber");
  model::Model built =
      model::assemble(mesh, directions, ligament, areas.femur, areas.tibia, config.model,
                      config.tetmesh.footprint_rims ? model::FootprintRule::faces_inside_rim
                                                    : model::FootprintRule::nearest_triangle);

  // The bones, repaired once: to close the footprints where the ligament lies in them, and
  // beside the model for flexion and pictures. A user's surface is written in; one already there
  // (from a label map) is kept as it is; a stale one of an earlier build goes.
  std::optional<TriangleSurface> femur, tibia;
  std::vector<std::string> bones;
  for (auto& [file, name, surface] : {std::tuple{config.femur, files::femur, &femur},
                                      std::tuple{config.tibia, files::tibia, &tibia}}) {
    const fs::path target = dir / name;
    std::error_code ignored;
    if (file.empty()) {
      fs::remove(target, ignored);
      continue;
    }
    *surface = load_bone(file);
    if (!fs::equivalent(file, target, ignored))
      write_vtk(io::to_polydata(**surface), target);
    bones.push_back(name);
  }
  const model::FootprintClosing closed =
      model::close_footprints_in_bones(built, femur ? &*femur : nullptr, tibia ? &*tibia : nullptr);

  vtkSmartPointer<vtkUnstructuredGrid> grid;
  if (tet10.rows() == 0) {
    grid = io::to_unstructured_grid(built.mesh);
  } else {
    sim::flag_mid_edge_nodes(tet10, built.femur_nodes);
    sim::flag_mid_edge_nodes(tet10, built.tibia_nodes);
    grid = io::to_unstructured_grid(QuadraticTetMesh{built.mesh.V, tet10});
    io::add_array(grid->GetCellData(), sim::kFibersAtPoints,
                  (1.0 + config.model.in_situ_strain) *
                      io::get_array(fibers_grid->GetCellData(), sim::kFibersAtPoints));
  }
  io::add_array(grid->GetCellData(), "fiber", built.fibers);
  io::add_flags(grid->GetPointData(), "femur_attached", built.femur_nodes);
  io::add_flags(grid->GetPointData(), "tibia_attached", built.tibia_nodes);
  write_vtk(grid, dir / files::model);

  Eigen::Vector3d femoral_mean = Eigen::Vector3d::Zero();
  for (int v : areas.femur)
    femoral_mean += ligament.V.row(v).transpose();
  femoral_mean /= static_cast<double>(areas.femur.size());
  model::Axis axis = model::default_flexion_axis(ligament, femoral_mean);
  if (config.flexion.axis_given)
    axis = {config.flexion.axis_point_mm, config.flexion.axis_direction.normalized()};
  write_scene(dir / files::scene, config, axis, bones);

  const auto count = [](const std::vector<bool>& flags) {
    return std::count(flags.begin(), flags.end(), true);
  };
  return {
      {"tets", built.mesh.T.rows()},
      {"nodes_per_tet", tet10.rows() == 0 ? 4 : 10},
      {"nodes", built.mesh.V.rows()},
      {"boundary_nodes", built.boundary_nodes},
      {"femur_nodes", count(built.femur_nodes)},
      {"tibia_nodes", count(built.tibia_nodes)},
      {"footprint_area_mm2",
       {{"femur", built.femur_area_mm2},
        {"tibia", built.tibia_area_mm2},
        {"rule", config.tetmesh.footprint_rims
                     ? "the boundary faces whose centroid lies inside the attachment area's rim"
                     : "the boundary faces whose three corners are bound"}}},
      {"footprint_nodes_unbound",
       {{"femur", built.femur_nodes_unbound},
        {"tibia", built.tibia_nodes_unbound},
        {"rule", "a node the attachment rule binds that is no corner of a boundary face bound "
                 "to the same bone (a point constraint) stays free"}}},
      {"footprint_nodes_inside_bone_added",
       {{"femur", closed.femur_nodes},
        {"tibia", closed.tibia_nodes},
        {"rule", "a node inside its bone whose tet neighbours are mostly bound to it; then "
                 "the interior nodes inside it that share a tet with the footprint, ring by ring "
                 "where no free surface node is beside them"}}},
      {"fiber_length", 1.0 + config.model.in_situ_strain},
      {"flexion_axis",
       {{"point_mm", {axis.point.x(), axis.point.y(), axis.point.z()}},
        {"direction", {axis.direction.x(), axis.direction.y(), axis.direction.z()}},
        {"rule", config.flexion.axis_given ? "given"
                                           : "femoral attachment, thinnest principal direction"}}}};
}

} // namespace ligsim::pipeline
