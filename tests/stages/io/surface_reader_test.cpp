#include "common/error.hpp"
#include "stages/geometry/surface_topology.hpp"
#include "stages/io/surface_reader.hpp"
#include "stages/io/vtk_convert.hpp"
#include "stages/synthetic/shapes.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <vtkOBJWriter.h>
#include <vtkPLYWriter.h>
#include <vtkPolyData.h>
#include <vtkPolyDataWriter.h>
#include <vtkSTLWriter.h>
#include <vtkXMLPolyDataWriter.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>

using namespace ligsim;
namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string& name)
{
  const fs::path dir = fs::temp_directory_path() / "ligsim_io_test";
  fs::create_directories(dir);
  return dir / name;
}

template <class Writer>
fs::path write_with(vtkPolyData* data, const std::string& name, bool binary = true)
{
  const fs::path file = scratch(name);
  auto writer = vtkSmartPointer<Writer>::New();
  writer->SetInputData(data);
  writer->SetFileName(file.c_str());
  if constexpr (std::is_same_v<Writer, vtkSTLWriter> || std::is_same_v<Writer, vtkPLYWriter> ||
                std::is_same_v<Writer, vtkPolyDataWriter>) {
    if (binary)
      writer->SetFileTypeToBinary();
    else
      writer->SetFileTypeToASCII();
  }
  EXPECT_EQ(writer->Write(), 1);
  return file;
}

void expect_same_shape(const TriangleSurface& read, const TriangleSurface& original)
{
  EXPECT_EQ(read.V.rows(), original.V.rows());
  EXPECT_EQ(read.F.rows(), original.F.rows());
  EXPECT_NEAR(signed_volume(read), signed_volume(original), 1e-4 * signed_volume(original));
  EXPECT_TRUE(check_topology(read).closed_manifold());
}

} // namespace

TEST(SurfaceReader, ReadsEveryFormatWithMergedVertices)
{
  const TriangleSurface cylinder = synthetic::cylinder(3.0, 20.0, 32).surface;
  auto data = io::to_polydata(cylinder);
  expect_same_shape(io::read_surface(write_with<vtkSTLWriter>(data, "c_bin.stl")), cylinder);
  expect_same_shape(io::read_surface(write_with<vtkSTLWriter>(data, "c_ascii.stl", false)),
                    cylinder);
  expect_same_shape(io::read_surface(write_with<vtkOBJWriter>(data, "c.obj")), cylinder);
  expect_same_shape(io::read_surface(write_with<vtkPLYWriter>(data, "c.ply")), cylinder);
  expect_same_shape(io::read_surface(write_with<vtkXMLPolyDataWriter>(data, "c.vtp")), cylinder);
  expect_same_shape(io::read_surface(write_with<vtkPolyDataWriter>(data, "c.vtk")), cylinder);
  // The pre-checks of PLY and legacy VTK know both encodings of VTK's own writers.
  expect_same_shape(io::read_surface(write_with<vtkPLYWriter>(data, "c_ascii.ply", false)),
                    cylinder);
  expect_same_shape(io::read_surface(write_with<vtkPolyDataWriter>(data, "c_ascii.vtk", false)),
                    cylinder);
}

TEST(SurfaceReader, ReadsTheRealMcl)
{
  const TriangleSurface mcl = io::read_surface(
      fs::path(LIGSIM_SOURCE_DIR) / "data/vhf-right-knee/VHF_Right_Ligament_MCL_smooth.stl");
  EXPECT_EQ(mcl.V.rows(), 1557);
  EXPECT_EQ(mcl.F.rows(), 3110);
  EXPECT_NO_THROW(io::require_closed_manifold(mcl, "MCL"));
}

TEST(SurfaceReader, BadInputsAreClearErrors)
{
  EXPECT_THROW(io::read_surface(scratch("missing.stl")), InputError);
  std::ofstream(scratch("x.xyz")) << "1 2 3\n";
  EXPECT_THROW(io::read_surface(scratch("x.xyz")), InputError);
  std::ofstream(scratch("garbage.stl")) << "this is not an stl file\n";
  EXPECT_THROW(io::read_surface(scratch("garbage.stl")), InputError);

  // A binary STL whose second triangle carries a NaN, as a broken export writes it.
  {
    std::ofstream stl(scratch("nan.stl"), std::ios::binary);
    const std::string header(80, ' ');
    stl.write(header.data(), 80);
    const std::uint32_t count = 2;
    stl.write(reinterpret_cast<const char*>(&count), 4);
    const float triangles[2][12] = {{0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0},
                                    {0, 0, 1, 5, 5, 5, 6, 5, 5, 5, std::nanf(""), 5}};
    const std::uint16_t attribute = 0;
    for (const auto& t : triangles) {
      stl.write(reinterpret_cast<const char*>(t), sizeof(t));
      stl.write(reinterpret_cast<const char*>(&attribute), 2);
    }
  }
  try {
    io::read_surface(scratch("nan.stl"));
    FAIL() << "NaN accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("non-finite"), std::string::npos) << e.what();
  }
}

TEST(SurfaceReader, TruncatedBinaryStlSaysSo)
{
  const TriangleSurface cylinder = synthetic::cylinder(3.0, 20.0, 32).surface;
  const fs::path whole = write_with<vtkSTLWriter>(io::to_polydata(cylinder), "whole.stl");
  const auto size = fs::file_size(whole);
  const fs::path cut = scratch("cut.stl");
  fs::copy_file(whole, cut, fs::copy_options::overwrite_existing);
  fs::resize_file(cut, size - 75); // one and a half triangles short
  try {
    io::read_surface(cut);
    FAIL() << "truncated STL accepted";
  } catch (const InputError& e) {
    const std::string expected =
        fmt::format("truncated binary STL: its header announces {} triangles ({} bytes) but the "
                    "file holds {} bytes ({} whole triangles)",
                    cylinder.F.rows(), size, size - 75, cylinder.F.rows() - 2);
    EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
  }
}

TEST(SurfaceReader, NonManifoldEdgeIsRejectedWithItsVertices)
{
  // A box with a closed tetrahedron hung on the edge of its first triangle: four triangles there.
  TriangleSurface box = synthetic::box({0, 0, 0}, {1, 1, 1});
  const int a = box.F(0, 0), b = box.F(0, 1);
  const int w = static_cast<int>(box.V.rows()), x = w + 1;
  box.V.conservativeResize(box.V.rows() + 2, 3);
  box.V.row(w) << 0.5, -1.0, -1.0;
  box.V.row(x) << 0.5, -1.5, -0.5;
  box.F.conservativeResize(box.F.rows() + 4, 3);
  box.F.bottomRows(4) << a, b, w, a, w, x, a, x, b, b, x, w;
  try {
    io::require_closed_manifold(box, "ligament surface");
    FAIL() << "non-manifold surface accepted";
  } catch (const InputError& e) {
    const Eigen::Vector3d p = box.V.row(std::min(a, b)), q = box.V.row(std::max(a, b));
    const std::string where =
        fmt::format("vertices {} ({:.2f}, {:.2f}, {:.2f}) and {} ({:.2f}, {:.2f}, {:.2f}) mm",
                    std::min(a, b), p.x(), p.y(), p.z(), std::max(a, b), q.x(), q.y(), q.z());
    EXPECT_NE(std::string(e.what()).find(where), std::string::npos) << e.what();
  }
}

TEST(SurfaceReader, OpenSurfaceIsRejectedWithLocation)
{
  TriangleSurface open = synthetic::cylinder(3.0, 20.0, 32).surface;
  open.F.conservativeResize(open.F.rows() - 1, 3);
  try {
    io::require_closed_manifold(open, "ligament surface");
    FAIL() << "open surface accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("3 boundary edges"), std::string::npos) << e.what();
  }
}

TEST(SurfaceReader, OrientOutwardFlipsAnInvertedSurface)
{
  TriangleSurface box = synthetic::box({0, 0, 0}, {1, 1, 1});
  box.F.col(1).swap(box.F.col(2));
  EXPECT_LT(signed_volume(box), 0.0);
  io::orient_outward(box);
  EXPECT_NEAR(signed_volume(box), 1.0, 1e-12);
}
