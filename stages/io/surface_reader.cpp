#include "stages/io/surface_reader.hpp"

#include "common/error.hpp"
#include "common/joined_names.hpp"
#include "common/vtk_files.hpp"
#include "stages/geometry/surface_query.hpp"
#include "stages/geometry/surface_topology.hpp"
#include "stages/io/gltf_reader.hpp"
#include "stages/io/legacy_vtk_check.hpp"
#include "stages/io/obj_reader.hpp"
#include "stages/io/ply_check.hpp"
#include "stages/io/stl_reader.hpp"
#include "stages/io/surface_path.hpp"
#include "stages/io/vtk_convert.hpp"
#include "stages/io/vtp_check.hpp"

#include <vtkAppendPolyData.h>
#include <vtkCellArray.h>
#include <vtkCleanPolyData.h>
#include <vtkDataArray.h>
#include <vtkPLYReader.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkPolyDataReader.h>
#include <vtkSmartPointer.h>
#include <vtkTriangleFilter.h>
#include <vtkXMLPolyDataReader.h>

#include <algorithm>
#include <cctype>
#include <cmath>

namespace ligsim::io {

namespace fs = std::filesystem;

namespace {

std::string lower_extension(const fs::path& file)
{
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

template <class Reader> vtkSmartPointer<vtkPolyData> run_reader(const fs::path& file)
{
  auto reader = vtkSmartPointer<Reader>::New();
  const VtkErrorTrap trap(reader);
  reader->SetFileName(file.c_str());
  reader->Update();
  if (trap.caught())
    fail("cannot read '{}': {}", file.string(), trap.message());
  return reader->GetOutput();
}

vtkSmartPointer<vtkPolyData> read_polydata(const fs::path& file, const std::string& mesh)
{
  const std::string extension = lower_extension(file);
  // glTF is checked by our code, then read by VTK (its reader trusts the file). Several meshes
  // joined by '+' are one surface: an atlas' bone in pieces (its vertices where the pieces
  // meet coincide, and are merged below).
  if (extension == ".glb" || extension == ".gltf") {
    if (mesh.find('+') == std::string::npos)
      return read_gltf(file, mesh);
    auto joined = vtkSmartPointer<vtkAppendPolyData>::New();
    for (const std::string& piece : joined_names(mesh, fmt::format("'{}#{}'", file.string(), mesh)))
      joined->AddInputData(read_gltf(file, piece));
    joined->Update();
    return joined->GetOutput();
  }
  // STL and OBJ are read by our own code; PLY, VTP and legacy VTK are checked before VTK reads
  // them (its readers crash on truncated files and trust the counts).
  if (extension == ".stl")
    return read_stl(file);
  if (extension == ".obj")
    return read_obj(file);
  if (extension == ".ply") {
    check_ply(file);
    return run_reader<vtkPLYReader>(file);
  }
  if (extension == ".vtp") {
    check_vtp(file);
    return run_reader<vtkXMLPolyDataReader>(file);
  }
  if (extension == ".vtk") {
    check_legacy_vtk(file);
    return run_reader<vtkPolyDataReader>(file);
  }
  fail("'{}': unknown surface format '{}' (use .stl, .obj, .ply, .vtp, .vtk, .glb or .gltf)",
       file.string(), extension);
}

/// VTK's readers pass cells through unchecked: a face naming vertex 23333 of 3 makes the filters
/// below read past the points, and a face of fewer than 3 corners makes vtkPolyData's cell map
/// fail to build (and GetCellPoints then calls through a null map). Walks the cell arrays
/// themselves, which need no map.
void check_cells(vtkPolyData* raw, const fs::path& file)
{
  const vtkIdType point_count = raw->GetNumberOfPoints();
  struct Kind {
    vtkCellArray* cells;
    const char* name;
    vtkIdType min_corners;
  };
  vtkIdType face = 0; // counted over all kinds, in VTK's cell order
  for (const Kind& kind :
       {Kind{raw->GetVerts(), "vertex cell", 1}, Kind{raw->GetLines(), "line", 2},
        Kind{raw->GetPolys(), "face", 3}, Kind{raw->GetStrips(), "strip", 3}}) {
    if (kind.cells == nullptr)
      continue;
    for (vtkIdType c = 0; c < kind.cells->GetNumberOfCells(); ++c, ++face) {
      vtkIdType size = 0;
      const vtkIdType* ids = nullptr;
      kind.cells->GetCellAtId(c, size, ids);
      if (size < kind.min_corners)
        fail("'{}': {} {} has {} corner(s), a {} needs at least {}", file.string(), kind.name, face,
             size, kind.name, kind.min_corners);
      for (vtkIdType k = 0; k < size; ++k)
        if (ids[k] < 0 || ids[k] >= point_count)
          fail("'{}': {} {} refers to vertex {}, but the file has {} vertices", file.string(),
               kind.name, face, ids[k], point_count);
    }
  }
}

/// "vertices 12 (x, y, z) and 40 (x, y, z) mm", for messages that say where an edge is.
std::string edge_text(const TriangleSurface& surface, const std::pair<int, int>& edge)
{
  const Eigen::Vector3d a = surface.V.row(edge.first), b = surface.V.row(edge.second);
  return fmt::format("vertices {} ({:.2f}, {:.2f}, {:.2f}) and {} ({:.2f}, {:.2f}, {:.2f}) mm",
                     edge.first, a.x(), a.y(), a.z(), edge.second, b.x(), b.y(), b.z());
}

} // namespace

TriangleSurface read_surface(const fs::path& path,
                             std::map<std::string, Eigen::VectorXd>* point_arrays)
{
  const SurfacePath source = split_surface_path(path);
  if (!fs::is_regular_file(source.file))
    fail("missing surface file '{}'", source.file.string());
  vtkSmartPointer<vtkPolyData> raw = read_polydata(source.file, source.mesh);
  if (raw == nullptr || raw->GetNumberOfPoints() == 0)
    fail("'{}' holds no points (unreadable or empty)", path.string());

  // Check coordinates before merging: a NaN point would poison the merge.
  for (vtkIdType i = 0; i < raw->GetNumberOfPoints(); ++i) {
    double p[3];
    raw->GetPoint(i, p);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      fail("'{}': vertex {} has a non-finite coordinate ({}, {}, {})", path.string(), i, p[0], p[1],
           p[2]);
  }

  check_cells(raw, path);

  auto triangles = vtkSmartPointer<vtkTriangleFilter>::New();
  triangles->SetInputData(raw);
  triangles->PassVertsOff();
  triangles->PassLinesOff();
  auto clean = vtkSmartPointer<vtkCleanPolyData>::New();
  clean->SetInputConnection(triangles->GetOutputPort());
  clean->PointMergingOn();
  clean->SetTolerance(0.0);
  clean->ConvertPolysToLinesOff();
  clean->ConvertLinesToPointsOff();
  clean->ConvertStripsToPolysOff();
  clean->Update();

  vtkPolyData* cleaned = clean->GetOutput();
  TriangleSurface surface = from_polydata(cleaned);
  if (surface.F.rows() == 0)
    fail("'{}' holds no triangles", path.string());
  if (point_arrays != nullptr) {
    vtkPointData* data = cleaned->GetPointData();
    for (int a = 0; a < data->GetNumberOfArrays(); ++a) {
      vtkDataArray* array = data->GetArray(a);
      if (array == nullptr || array->GetName() == nullptr || array->GetNumberOfComponents() != 1)
        continue;
      Eigen::VectorXd values(array->GetNumberOfTuples());
      for (Eigen::Index v = 0; v < values.size(); ++v)
        values[v] = array->GetTuple1(v);
      (*point_arrays)[array->GetName()] = values;
    }
  }
  return surface;
}

void orient_outward(TriangleSurface& surface)
{
  if (signed_volume(surface) < 0.0)
    surface.F.col(1).swap(surface.F.col(2));
}

void require_closed_manifold(const TriangleSurface& surface, const std::string& what)
{
  const TopologyReport report = check_topology(surface);
  if (report.boundary_edges > 0) {
    const Eigen::Vector3d& p = report.boundary_edge_midpoints.front();
    fail("{} is not closed: {} boundary edges, within x {:.2f}..{:.2f}, y {:.2f}..{:.2f}, "
         "z {:.2f}..{:.2f} mm (first at {:.2f}, {:.2f}, {:.2f})",
         what, report.boundary_edges, report.boundary_min.x(), report.boundary_max.x(),
         report.boundary_min.y(), report.boundary_max.y(), report.boundary_min.z(),
         report.boundary_max.z(), p.x(), p.y(), p.z());
  }
  if (report.nonmanifold_edges > 0)
    fail("{} is not a manifold: {} edges are shared by three or more triangles (first: {})", what,
         report.nonmanifold_edges, edge_text(surface, report.nonmanifold_edge_list.front()));
  if (report.inconsistent_edges > 0)
    fail("{} is not consistently oriented: {} edges are run the same way by both triangles "
         "(first: {})",
         what, report.inconsistent_edges,
         edge_text(surface, report.inconsistent_edge_list.front()));
  const auto crossings = self_intersections(surface, 1);
  if (!crossings.empty()) {
    const auto [a, b] = crossings.front();
    const Eigen::Vector3d p = surface.V.row(surface.F(a, 0));
    fail("{} intersects itself: triangles {} and {} cross near ({:.2f}, {:.2f}, {:.2f}) mm", what,
         a, b, p.x(), p.y(), p.z());
  }
}

} // namespace ligsim::io
