// The fuzzing findings of tests/fuzz/findings (each crashed or exhausted VTK 9.1's readers) and
// the checks that fixed them: every one is now one InputError naming the file and the place.

#include "common/error.hpp"
#include "stages/io/metaimage_check.hpp"
#include "stages/io/surface_reader.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

using namespace ligsim;
namespace fs = std::filesystem;

namespace {

fs::path finding(const std::string& name)
{
  return fs::path(LIGSIM_SOURCE_DIR) / "tests/fuzz/findings" / name;
}

fs::path scratch(const std::string& name, const std::string& content)
{
  const fs::path dir = fs::temp_directory_path() / "ligsim_io_findings_test";
  fs::create_directories(dir);
  std::ofstream(dir / name, std::ios::binary) << content;
  return dir / name;
}

/// The InputError's message of read_surface(file); fails the test if there is none.
std::string error_of(const fs::path& file)
{
  try {
    io::read_surface(file);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << file << " was read without an error";
  return {};
}

void expect_error(const fs::path& file, const std::string& part)
{
  const std::string message = error_of(file);
  EXPECT_NE(message.find(file.string()), std::string::npos) << message;
  EXPECT_NE(message.find(part), std::string::npos) << message;
}

const std::string tet_ply_header = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\n"
                                   "property float y\nproperty float z\nelement face 4\n"
                                   "property list uchar int vertex_indices\nend_header\n";
const std::string tet_ply_body = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
                                 "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

} // namespace

TEST(ReaderFindings, TruncatedPlyHeader)
{
  expect_error(finding("ply_truncated_header.ply"), "line 4: expected 'property <type> <name>'");
}

TEST(ReaderFindings, TruncatedPlyVertices)
{
  expect_error(finding("ply_truncated_vertices.ply"), "line 8: unknown header line starting 'p'");
  // A whole header with the body cut in the faces.
  expect_error(scratch("cut_faces.ply", tet_ply_header + tet_ply_body.substr(0, 30)),
               "line 14: face 0: expected a number for 'vertex_indices', found 'the line end'");
}

TEST(ReaderFindings, PlyCountsAgainstTheFile)
{
  const TriangleSurface tet = io::read_surface(scratch("tet.ply", tet_ply_header + tet_ply_body));
  EXPECT_EQ(tet.F.rows(), 4);
  // A binary body shorter than its counts: 4 vertices of 12 bytes, then the faces.
  std::string binary = tet_ply_header;
  binary.replace(binary.find("ascii"), 5, "binary_little_endian");
  binary += std::string(48, '\0') + std::string(1, '\3') + std::string(6, '\0');
  expect_error(scratch("cut_binary.ply", binary),
               "byte 218: a list needs 12 bytes, but the file ends 6 bytes later");
  // Huge element counts in a tiny file.
  std::string huge = tet_ply_header;
  huge.replace(huge.find("vertex 4"), 8, "vertex 2000000000");
  expect_error(scratch("huge.ply", huge + tet_ply_body),
               "line 14: vertex 4 has 4 numbers, 1 more than its properties");
}

TEST(ReaderFindings, TruncatedLegacyVtkPolygons)
{
  expect_error(finding("vtk_truncated_polygons.vtk"),
               "expected the cell list, but the file ends (truncated?)");
}

TEST(ReaderFindings, FacesOfFewerThanThreeCorners)
{
  // A face of 2 corners (PLY) or of 1 (legacy VTK): vtkPolyData's cell map failed to build and
  // read_surface called through its null pointer (UBSan, then SEGV).
  expect_error(finding("ply_two_corner_face.ply"),
               "face 2 has 2 corner(s), a face needs at least 3");
  expect_error(finding("vtk_one_corner_polygon.vtk"),
               "face 1 has 1 corner(s), a face needs at least 3");
}

TEST(ReaderFindings, PlyBlankHeaderLine)
{
  // vtkPLYReader freed an uninitialised pointer (ASan SEGV in ply_close).
  expect_error(finding("ply_blank_header_line.ply"), "line 4: a blank line in the header");
}

TEST(ReaderFindings, PlyHeaderOrderAndNames)
{
  // Found by hand next to the campaign's findings: faces declared before the vertices, or two
  // properties of one name, made vtkPLYReader crash (ASan SEGV).
  expect_error(finding("ply_faces_before_vertices.ply"),
               "the face element comes before the vertex element");
  expect_error(finding("ply_property_declared_twice.ply"),
               "line 9: property 'vertex_indices' is declared twice in element 'face'");
}

TEST(ReaderFindings, PlyLastLineWithoutLineEnd)
{
  // vtkPLYReader freed a word list twice (ASan double-free) when the last face had no '\n'.
  expect_error(finding("ply_last_line_without_line_end.ply"),
               "line 17: face 3: the last line has no line end (truncated?)");
  std::string body = tet_ply_body;
  body.pop_back();
  expect_error(scratch("cut.ply", tet_ply_header + body + " \r"), "face 3: the last line");
  EXPECT_EQ(io::read_surface(scratch("whole.ply", tet_ply_header + tet_ply_body)).F.rows(), 4);
}

TEST(ReaderFindings, VtpCountsAreWholeNumbers)
{
  // NumberOfComponents="-3": vtkXMLReader sized a vector from it (uncaught std::length_error).
  expect_error(finding("vtp_negative_components.vtp"),
               "line 5: NumberOfComponents=\"-3\": expected a whole number from 1 to 1024");
  const std::string head = "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\">\n<PolyData>\n";
  expect_error(scratch("spaces.vtp", head + "<Piece NumberOfPoints = '-4' NumberOfPolys=\"1\">\n"),
               "line 4: NumberOfPoints=\"-4\": expected a whole number from 0 to 2147483647");
  expect_error(scratch("huge.vtp", head + "<Piece NumberOfPoints=\"4\" NumberOfPolys=\"9e9\">\n"),
               "line 4: NumberOfPolys=\"9e9\": expected a whole number");
}

TEST(ReaderFindings, MetaImageDimensionCount)
{
  // NDims = -3: ITK's MetaIO read it as a huge count and looped until the fuzzer's timeout.
  const fs::path file = finding("mha_negative_ndims.mha");
  try {
    io::check_metaimage_header(file);
    ADD_FAILURE() << "NDims = -3 was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "'" + file.string() +
                                         "' line 2: NDims = '-3': expected a whole number "
                                         "from 1 to 10");
  }
  const std::string tail = "DimSize = 4 3 2\nElementType = MET_UCHAR\nElementDataFile = LOCAL\n";
  EXPECT_NO_THROW(io::check_metaimage_header(scratch("three.mha", "NDims = 3\n" + tail + "\x01")));
  EXPECT_NO_THROW(io::check_metaimage_header(scratch("ten.mha", "NDims=10\n" + tail)));
  // The data after ElementDataFile are not header lines.
  EXPECT_NO_THROW(
      io::check_metaimage_header(scratch("data.mha", "NDims = 3\n" + tail + "NDims = 0\n")));
  EXPECT_THROW(io::check_metaimage_header(scratch("eleven.mha", "NDims = 11\n" + tail)),
               InputError);
  EXPECT_THROW(
      io::check_metaimage_header(scratch("zero.mha", "ObjectType = Image\nNDims = 0\n" + tail)),
      InputError);
}

TEST(ReaderFindings, LegacyVtkCellsNameExistingPoints)
{
  const std::string head = "# vtk DataFile Version 3.0\ntet\nASCII\nDATASET POLYDATA\n"
                           "POINTS 4 float\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
  EXPECT_EQ(io::read_surface(scratch("tet.vtk", head + "POLYGONS 4 16\n3 0 2 1\n3 0 1 3\n"
                                                       "3 0 3 2\n3 1 2 3\n"))
                .F.rows(),
            4);
  expect_error(scratch("far.vtk", head + "POLYGONS 1 4\n3 0 2 9\n"),
               "cell 0 refers to point 9, but there are 4 points");
  expect_error(scratch("long.vtk", head + "POLYGONS 1 4\n30 0 2 1\n"),
               "cell 0 of 1 does not fit in the cell list of 4 numbers");
  expect_error(scratch("data.vtk", head + "POLYGONS 1 4\n3 0 2 1\nPOINT_DATA 5\n"),
               "the POINT_DATA count is 5, but the file has 4");
  expect_error(scratch("version.vtk", "# vtk DataFile Version five\nt\nASCII\n"),
               "line 1: a legacy VTK file starts with '# vtk DataFile Version <major>.<minor>'");
  expect_error(scratch("image.vtk", "# vtk DataFile Version 3.0\nt\nASCII\n"
                                    "DATASET STRUCTURED_POINTS\n"),
               "line 4: dataset type 'STRUCTURED_POINTS' is not a surface");
}

TEST(ReaderFindings, StlSolidHeaderWithBinaryBytes)
{
  // 232 bytes starting with "solid", non-ASCII bytes inside, and bytes 80..83 announcing
  // 1667310885 triangles: vtkSTLReader took it for binary and allocated 8 GB. Its size is not
  // 84 + 50 n for that n, so it is an ASCII file, and a broken one.
  expect_error(finding("stl_solid_header_binary_8gb.stl"),
               "line 2: expected 'facet' or 'endsolid', found 'f%%%");
}

TEST(ReaderFindings, BinaryStlMayStartWithSolid)
{
  // Some exporters start binary files with "solid"; a size of exactly 84 + 50 n says binary.
  std::string stl = "solid exported as binary";
  stl.resize(80, ' ');
  const std::uint32_t count = 1;
  stl.append(reinterpret_cast<const char*>(&count), 4);
  const float triangle[12] = {0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0};
  stl.append(reinterpret_cast<const char*>(triangle), sizeof(triangle));
  stl.append(2, '\0');
  const TriangleSurface surface = io::read_surface(scratch("solid_binary.stl", stl));
  EXPECT_EQ(surface.F.rows(), 1);
  EXPECT_EQ(surface.V.rows(), 3);
  EXPECT_DOUBLE_EQ(surface.V.col(0).maxCoeff(), 1.0);
  // One byte more and it is neither.
  expect_error(scratch("solid_binary_long.stl", stl + " "),
               "line 1: expected 'facet' or 'endsolid'");
}

TEST(ReaderFindings, AsciiStlStructure)
{
  const std::string facet = "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                            "vertex 0 1 0\nendloop\nendfacet\n";
  expect_error(scratch("no_end.stl", "solid a\n" + facet), "line 9: expected 'facet' or "
                                                           "'endsolid', but the file ends");
  expect_error(scratch("two_vertices.stl",
                       "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                       "endloop\nendfacet\nendsolid a\n"),
               "line 6: expected 'vertex', found 'endloop'");
  expect_error(scratch("letters.stl", "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 x 0\n"),
               "line 4: expected a vertex coordinate, found 'x'");
}

TEST(ReaderFindings, ObjFaceWithDanglingTextureSlash)
{
  // `f 1 3 2333/`: vtkOBJReader read out of bounds (SEGV).
  expect_error(finding("obj_texture_index_in_reader.obj"),
               "line 5: face corner '3' refers to vertex 3, but 2 are defined above it");
  expect_error(scratch("slash.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3/\n"),
               "line 4: face corner '3/' ends in '/' without an index");
}

TEST(ReaderFindings, ObjCornerFormsAndNegativeIndices)
{
  const std::string vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvt 0 0\nvn 0 0 1\n";
  const TriangleSurface tet = io::read_surface(
      scratch("tet.obj", vertices + "# comment\ng part\nf 1 3 2\nf 1/1 2/1 4/1\n"
                                    "f 1//1 4//1 3//1\nf -3/-1/-1 -2/1/1 -1/1/-1\n"));
  EXPECT_EQ(tet.V.rows(), 4);
  EXPECT_EQ(tet.F.rows(), 4);
  expect_error(scratch("texture.obj", vertices + "f 1/2 2 3\n"),
               "line 7: face corner '1/2' refers to texture coordinate 2, but 1 are defined");
  expect_error(scratch("normal.obj", vertices + "f 1//-2 2 3\n"),
               "line 7: face corner '1//-2' refers to normal -2, but 1 are defined");
  expect_error(scratch("zero.obj", vertices + "f 0 2 3\n"), "refers to vertex 0");
  expect_error(scratch("word.obj", vertices + "f 1 2 x\n"), "vertex index 'x' is not an integer");
  expect_error(scratch("short.obj", "v 1 2\n"), "line 1: a vertex needs three coordinates");
}
