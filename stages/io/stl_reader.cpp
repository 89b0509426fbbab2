#include "stages/io/stl_reader.hpp"

#include "common/error.hpp"
#include "stages/io/text_cursor.hpp"

#include <vtkCellArray.h>
#include <vtkPoints.h>

#include <cstdint>
#include <cstring>
#include <string>

namespace ligsim::io {

namespace fs = std::filesystem;

namespace {

constexpr std::size_t header_bytes = 84;   // 80 bytes of text, then the triangle count
constexpr std::size_t triangle_bytes = 50; // normal, 3 vertices (float32 each), 2 attribute bytes

vtkSmartPointer<vtkPolyData> make_polydata(vtkPoints* points)
{
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  const vtkIdType triangles = points->GetNumberOfPoints() / 3;
  cells->AllocateExact(triangles, 3 * triangles);
  for (vtkIdType t = 0; t < triangles; ++t) {
    const vtkIdType ids[3] = {3 * t, 3 * t + 1, 3 * t + 2};
    cells->InsertNextCell(3, ids);
  }
  auto data = vtkSmartPointer<vtkPolyData>::New();
  data->SetPoints(points);
  data->SetPolys(cells);
  return data;
}

std::uint32_t announced_count(const std::string& bytes)
{
  std::uint32_t count = 0;
  std::memcpy(&count, bytes.data() + 80, 4); // little-endian, as the format and x86 are
  return count;
}

vtkSmartPointer<vtkPolyData> read_binary(const std::string& bytes, std::uint32_t count)
{
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToFloat();
  points->SetNumberOfPoints(3 * static_cast<vtkIdType>(count));
  for (std::uint32_t t = 0; t < count; ++t) {
    const char* record = bytes.data() + header_bytes + triangle_bytes * t;
    for (int v = 0; v < 3; ++v) {
      float xyz[3];
      std::memcpy(xyz, record + 12 * (v + 1), sizeof(xyz)); // after the facet normal
      points->SetPoint(3 * static_cast<vtkIdType>(t) + v, xyz[0], xyz[1], xyz[2]);
    }
  }
  return make_polydata(points);
}

/// solid NAME, then per triangle: facet normal x y z / outer loop / vertex x y z (3 times) /
/// endloop / endfacet; endsolid NAME. Several solids in one file are read as one surface.
vtkSmartPointer<vtkPolyData> read_ascii(const fs::path& file, const std::string& bytes)
{
  TextCursor text(file, bytes);
  auto points = vtkSmartPointer<vtkPoints>::New();
  while (text.skip_space()) {
    text.expect("solid");
    text.next_line(); // the solid's name
    for (;;) {
      const std::string word = text.word("'facet' or 'endsolid'");
      if (word == "endsolid") {
        text.next_line();
        break;
      }
      if (word != "facet")
        text.fail_here("expected 'facet' or 'endsolid', found '{}'", word);
      text.expect("normal");
      for (int i = 0; i < 3; ++i)
        text.number("a normal component");
      text.expect("outer");
      text.expect("loop");
      for (int v = 0; v < 3; ++v) {
        text.expect("vertex");
        const double x = text.number("a vertex coordinate");
        const double y = text.number("a vertex coordinate");
        const double z = text.number("a vertex coordinate");
        points->InsertNextPoint(x, y, z);
      }
      text.expect("endloop");
      text.expect("endfacet");
    }
  }
  return make_polydata(points);
}

} // namespace

vtkSmartPointer<vtkPolyData> read_stl(const fs::path& file)
{
  const std::string bytes = read_bytes(file);
  if (bytes.size() >= header_bytes) {
    const std::uint32_t count = announced_count(bytes);
    const std::uintmax_t expected = header_bytes + triangle_bytes * std::uintmax_t{count};
    if (bytes.size() == expected)
      return read_binary(bytes, count);
  }
  const auto first = bytes.find_first_not_of(" \t\r\n");
  if (first != std::string::npos && bytes.compare(first, 5, "solid") == 0)
    return read_ascii(file, bytes);
  if (bytes.size() < header_bytes)
    fail("'{}' is neither an ASCII STL (it does not start with 'solid') nor a binary one (it "
         "holds {} bytes, less than the {}-byte header)",
         file.string(), bytes.size(), header_bytes);
  const std::uint32_t count = announced_count(bytes);
  const std::uintmax_t expected = header_bytes + triangle_bytes * std::uintmax_t{count};
  if (bytes.size() < expected)
    fail("'{}' is a truncated binary STL: its header announces {} triangles ({} bytes) but the "
         "file holds {} bytes ({} whole triangles)",
         file.string(), count, expected, bytes.size(),
         (bytes.size() - header_bytes) / triangle_bytes);
  fail("'{}' is a damaged binary STL: its header announces {} triangles ({} bytes) but the file "
       "holds {} bytes, {} more",
       file.string(), count, expected, bytes.size(), bytes.size() - expected);
}

} // namespace ligsim::io
