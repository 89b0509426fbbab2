/// The stages on the voxel image: centerline, field, fibers.

#include "pipeline/stage_graph/stage_files.hpp"

#include "common/error.hpp"
#include "common/vtk_files.hpp"
#include "stages/centerline/centerline.hpp"
#include "stages/fibers/fibers.hpp"
#include "stages/field/field.hpp"
#include "stages/geometry/grid_vdb.hpp"
#include "stages/geometry/grid_vti.hpp"
#include "stages/geometry/surface_query.hpp"
#include "stages/io/vtk_convert.hpp"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>

namespace ligsim::pipeline {

namespace fs = std::filesystem;

namespace {

Points positions(const TriangleSurface& surface, const std::vector<int>& vertices)
{
  Points points(static_cast<Eigen::Index>(vertices.size()), 3);
  for (std::size_t i = 0; i < vertices.size(); ++i)
    points.row(static_cast<Eigen::Index>(i)) = surface.V.row(vertices[i]);
  return points;
}

nlohmann::json point_json(const Eigen::Vector3d& p)
{
  return {p.x(), p.y(), p.z()};
}

/// Short segments along each tet's fiber through its centroid, for viewing in ParaView.
vtkSmartPointer<vtkPolyData> fiber_lines(const TetMesh& mesh, const Eigen::MatrixX3d& directions)
{
  auto points = vtkSmartPointer<vtkPoints>::New();
  auto lines = vtkSmartPointer<vtkCellArray>::New();
  for (Eigen::Index t = 0; t < mesh.T.rows(); ++t) {
    Eigen::Matrix<double, 4, 3> corners;
    for (int k = 0; k < 4; ++k)
      corners.row(k) = mesh.V.row(mesh.T(t, k));
    const Eigen::Vector3d centroid = corners.colwise().mean().transpose();
    double edge = 0.0;
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b)
        edge += (corners.row(a) - corners.row(b)).norm() / 6.0;
    const Eigen::Vector3d half = 0.4 * edge * directions.row(t).transpose();
    const Eigen::Vector3d a = centroid - half, b = centroid + half;
    const vtkIdType ids[2] = {points->InsertNextPoint(a.data()), points->InsertNextPoint(b.data())};
    lines->InsertNextCell(2, ids);
  }
  auto polydata = vtkSmartPointer<vtkPolyData>::New();
  polydata->SetPoints(points);
  polydata->SetLines(lines);
  io::add_array(polydata->GetCellData(), "fiber", directions);
  return polydata;
}

} // namespace

nlohmann::json run_centerline(const BuildConfig& config, const fs::path& dir)
{
  const TriangleSurface ligament = load_ligament(config);
  const StoredAttachments areas = load_attachments(dir);
  if (areas.femur.empty() || areas.tibia.empty())
    fail("'{}' marks no {} attachment vertex", (dir / files::attachments).string(),
         areas.femur.empty() ? "femoral" : "tibial");
  const Points femur = positions(ligament, areas.femur), tibia = positions(ligament, areas.tibia);
  const Eigen::Vector3d start = femur.colwise().mean().transpose();
  const Eigen::Vector3d end = tibia.colwise().mean().transpose();
  const centerline::Centerline line =
      centerline::extract(load_mask(dir), load_distance(dir), femur, tibia, config.centerline);

  auto polydata = io::polyline_to_polydata(line.points);
  io::add_array(polydata->GetPointData(), "tangent", line.tangents);
  write_vtk(polydata, dir / files::centerline);
  return {{"span", centerline::to_string(config.centerline.span)},
          {"points", line.points.rows()},
          {"length_mm", line.length_mm},
          {"voxel_path_steps", line.voxel_path.size()},
          {"voxel_path_cost", line.path_cost},
          {"start_mm", point_json(line.points.row(0).transpose())},
          {"end_mm", point_json(line.points.row(line.points.rows() - 1).transpose())},
          {"femoral_attachment_mean_mm", point_json(start)},
          {"tibial_attachment_mean_mm", point_json(end)}};
}

nlohmann::json run_field(const BuildConfig& config, const fs::path& dir)
{
  const SurfaceQuery query(load_ligament(config));
  const Polyline line = load_centerline(dir);
  const field::Field field = field::diffusion_field(load_mask(dir), line, query, config.field);
  vdb::write_grid(field.values, "D", dir / files::field_vdb);
  write_vti(field.values, "D", dir / files::field);
  nlohmann::json figures = grid_json(field.values);
  figures["method"] = field::to_string(config.field.method);
  if (config.field.method == field::Method::geometric) {
    figures["rays_missed"] = field.rays_missed;
    figures["voxels_behind_a_fold"] = field.clamped;
  } else {
    figures["cg_iterations"] = field.iterations;
    figures["relative_residual"] = field.residual;
  }
  return figures;
}

nlohmann::json run_fibers(const BuildConfig& config, const fs::path& dir)
{
  const TetMesh mesh = load_mesh(dir / files::mesh);
  const Polyline line = load_centerline(dir);
  const fibers::FiberField field(line, load_field(dir), load_mask(dir));
  const fibers::Result result = fibers::per_tet_directions(mesh, field, config.fibers);

  auto grid = io::to_unstructured_grid(mesh);
  io::add_array(grid->GetCellData(), "fiber", result.directions);
  write_vtk(grid, dir / files::fibers);
  write_vtk(fiber_lines(mesh, result.directions), dir / files::fiber_lines);
  return {{"tets", mesh.T.rows()},
          {"samples_per_tet", config.fibers.samples_per_tet},
          {"unprojected_samples", result.unprojected_samples},
          {"mean_angle_to_centerline_deg", result.mean_alignment_deg}};
}

} // namespace ligsim::pipeline
