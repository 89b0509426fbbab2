#include "pipeline/stage_graph/stage_files.hpp"

#include "common/error.hpp"
#include "common/vtk_files.hpp"
#include "stages/geometry/grid_vdb.hpp"
#include "stages/geometry/surface_query.hpp"
#include "stages/io/surface_reader.hpp"
#include "stages/io/vtk_convert.hpp"
#include "stages/voxelize/level_set.hpp"

#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>

#include <limits>

namespace ligsim::pipeline {

namespace fs = std::filesystem;

namespace {

/// Point data of the surface as read, moved onto the repaired surface's vertices (0 on vertices
/// added to fill holes).
void follow_repair(const std::vector<int>& source_vertex,
                   std::map<std::string, Eigen::VectorXd>& arrays)
{
  for (auto& [name, values] : arrays) {
    Eigen::VectorXd moved = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(source_vertex.size()));
    for (std::size_t v = 0; v < source_vertex.size(); ++v)
      if (source_vertex[v] >= 0)
        moved[static_cast<Eigen::Index>(v)] = values[source_vertex[v]];
    values = std::move(moved);
  }
}

} // namespace

TriangleSurface load_ligament(const BuildConfig& config,
                              std::map<std::string, Eigen::VectorXd>* arrays,
                              repair::Report* repairs)
{
  if (config.surface.empty())
    fail("no ligament surface given (--surface or [input] surface)");
  TriangleSurface surface = io::read_surface(config.surface, arrays);
  if (!config.strict) {
    repair::Result repaired = repair::repair_surface(surface);
    if (!repaired.report.empty()) {
      surface = std::move(repaired.surface);
      if (arrays != nullptr)
        follow_repair(repaired.source_vertex, *arrays);
    }
    if (repairs != nullptr)
      *repairs = std::move(repaired.report);
  }
  io::orient_outward(surface);
  io::require_closed_manifold(surface,
                              fmt::format("ligament surface '{}'", config.surface.string()));
  return surface;
}

std::optional<TriangleSurface> load_bone(const fs::path& file, repair::Report* repairs)
{
  if (file.empty())
    return std::nullopt;
  repair::Result repaired =
      repair::repair_bone(io::read_surface(file), fmt::format("bone surface '{}'", file.string()));
  if (repairs != nullptr)
    *repairs = std::move(repaired.report);
  return std::move(repaired.surface);
}

Mask load_mask(const fs::path& dir)
{
  return vdb::LevelSet::read(dir / files::mask_vdb).inside();
}
ScalarGrid load_distance(const fs::path& dir)
{
  return vdb::read_grid(dir / files::distance_vdb, "distance");
}
ScalarGrid load_field(const fs::path& dir)
{
  return vdb::read_grid(dir / files::field_vdb, "D");
}

Polyline load_centerline(const fs::path& dir)
{
  auto polydata = read_vtp(dir / files::centerline);
  const Eigen::MatrixXd tangents = io::get_array(polydata->GetPointData(), "tangent");
  return Polyline(io::points_of(polydata), tangents);
}

TetMesh load_mesh(const fs::path& file, QuadraticTetrahedra* tet10)
{
  try {
    return io::from_unstructured_grid(read_vtu(file), tet10);
  } catch (const InputError& error) {
    fail("{}: {}", file.string(), error.what());
  }
}

StoredAttachments load_attachments(const fs::path& dir)
{
  auto polydata = read_vtp(dir / files::attachments);
  const Eigen::MatrixXd femur = io::get_array(polydata->GetPointData(), "femur_attachment");
  const Eigen::MatrixXd tibia = io::get_array(polydata->GetPointData(), "tibia_attachment");
  StoredAttachments result;
  for (Eigen::Index v = 0; v < femur.rows(); ++v) {
    if (femur(v, 0) != 0.0)
      result.femur.push_back(static_cast<int>(v));
    if (tibia(v, 0) != 0.0)
      result.tibia.push_back(static_cast<int>(v));
  }
  return result;
}

void require_a_bone_nearby(const std::string& what, const TriangleSurface& ligament,
                           const std::vector<std::pair<std::string, TriangleSurface>>& bones)
{
  // The atlas ligaments lie up to 2.5 mm off their bones; a label map's touch them.
  constexpr double kReachMm = 5.0;
  if (bones.empty())
    return;
  std::string distances;
  for (const auto& [name, bone] : bones) {
    const SurfaceQuery query(bone);
    double nearest = std::numeric_limits<double>::infinity();
    for (Eigen::Index v = 0; v < ligament.V.rows(); ++v)
      nearest = std::min(nearest, query.distance(ligament.V.row(v).transpose()));
    if (nearest <= kReachMm)
      return;
    distances += fmt::format("{}{} {:.1f} mm", distances.empty() ? "" : ", ", name, nearest);
  }
  fail("{} touches no bone: it lies farther than {:.0f} mm from each ({}); a ligament joins two "
       "bones: check its label or surface",
       what, kReachMm, distances);
}

} // namespace ligsim::pipeline
