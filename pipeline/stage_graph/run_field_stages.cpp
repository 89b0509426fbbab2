/// The stages on the voxel image: centerline, field, fibers.

#include "pipeline/stage_graph/stage_files.hpp"

#include "common/error.hpp"
#include "common/vtk_files.hpp"
#include "sim/mesh/quadratic_tet.hpp"
#include "stages/centerline/centerline.hpp"
#include "stages/fibers/fibers.hpp"
#include "stages/field/field.hpp"
#include "stages/geometry/grid_vdb.hpp"
#include "stages/geometry/grid_vti.hpp"
#include "stages/geometry/surface_query.hpp"
#include "stages/io/vtk_convert.hpp"

#include <fmt/format.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <cmath>

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

/// The fiber at each point of the rule of sim::kQuadraticTetRuleDegree of every 10-node tet
/// (element-major, 3 columns per point), sampled from the field where the curved element puts
/// the point, its sense that of the element's fiber.
Eigen::MatrixXd fibers_at_points(const QuadraticTetMesh& mesh, const fibers::FiberField& field,
                                 const Eigen::MatrixX3d& per_tet)
{
  const sim::QuadratureRule rule = sim::tet_quadrature(sim::kQuadraticTetRuleDegree);
  const Eigen::Map<const Eigen::VectorXd> flat(mesh.V.data(), mesh.V.size());
  Eigen::MatrixXd fibers(mesh.T.rows(), 3 * static_cast<Eigen::Index>(rule.points.size()));
  for (Eigen::Index e = 0; e < mesh.T.rows(); ++e) {
    const sim::QuadraticTetRows X = sim::quadratic_tet_nodes(mesh.T, e, flat);
    for (std::size_t q = 0; q < rule.points.size(); ++q) {
      const Eigen::Vector3d x = X.transpose() * sim::quadratic_shape_functions(rule.points[q]);
      Eigen::Vector3d a = field.at(x).direction;
      if (a.dot(per_tet.row(e)) < 0.0)
        a = -a;
      fibers.block<1, 3>(e, 3 * static_cast<Eigen::Index>(q)) = a.transpose();
    }
  }
  return fibers;
}

/// How far the fibers at the points turn from their tet's (one sample each, where the tet's
/// averages several).
nlohmann::json points_json(const Eigen::MatrixXd& points, const Eigen::MatrixX3d& per_tet)
{
  double sum_deg = 0.0;
  int over_30 = 0;
  const Eigen::Index per_element = points.cols() / 3;
  for (Eigen::Index e = 0; e < points.rows(); ++e)
    for (Eigen::Index q = 0; q < per_element; ++q) {
      const double cosine = std::min(1.0, points.block<1, 3>(e, 3 * q).dot(per_tet.row(e)));
      const double degrees = std::acos(cosine) * 180.0 / M_PI;
      sum_deg += degrees;
      over_30 += degrees > 30.0;
    }
  return {
      {"array", sim::kFibersAtPoints},
      {"points_per_tet", per_element},
      {"mean_angle_to_tet_fiber_deg", sum_deg / static_cast<double>(points.rows() * per_element)},
      {"points_over_30_deg_from_tet_fiber", over_30},
      {"rule", "one fiber sampled at each point of the 4-point rule of every 10-node tet, "
               "where the curved tet puts it"}};
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
  QuadraticTetrahedra tet10;
  const TetMesh mesh = load_mesh(dir / files::mesh, &tet10);
  const Polyline line = load_centerline(dir);
  const fibers::FiberField field(line, load_field(dir), load_mask(dir));
  const fibers::Result result = fibers::per_tet_directions(mesh, field, config.fibers);

  vtkSmartPointer<vtkUnstructuredGrid> grid;
  Eigen::MatrixXd points; // 10-node tets: the fibers at their quadrature points
  if (tet10.rows() == 0) {
    grid = io::to_unstructured_grid(mesh);
  } else {
    grid = io::to_unstructured_grid(QuadraticTetMesh{mesh.V, tet10});
    points = fibers_at_points(QuadraticTetMesh{mesh.V, tet10}, field, result.directions);
    io::add_array(grid->GetCellData(), sim::kFibersAtPoints, points);
  }
  io::add_array(grid->GetCellData(), "fiber", result.directions);
  write_vtk(grid, dir / files::fibers);
  write_vtk(fiber_lines(mesh, result.directions), dir / files::fiber_lines);
  nlohmann::json figures = {{"tets", mesh.T.rows()},
                            {"samples_per_tet", config.fibers.samples_per_tet},
                            {"unprojected_samples", result.unprojected_samples},
                            {"mean_angle_to_centerline_deg", result.mean_alignment_deg}};
  if (tet10.rows() > 0)
    figures["fibers_at_points"] = points_json(points, result.directions);
  return figures;
}

} // namespace ligsim::pipeline
