#include "stages/geometry/grid_vti.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"

#include <fmt/format.h>
#include <zlib.h>

#include <fstream>
#include <limits>

namespace ligsim {

namespace {

template <class T> const char* vtk_type_name();
template <> const char* vtk_type_name<float>()
{
  return "Float32";
}
template <> const char* vtk_type_name<std::uint8_t>()
{
  return "UInt8";
}

void write_u64(std::ostream& out, std::uint64_t value)
{
  out.write(reinterpret_cast<const char*>(&value), sizeof value); // the header says LittleEndian
}

} // namespace

template <class T>
void write_vti(const Grid<T>& grid, const std::string& name, const std::filesystem::path& file)
{
  const int nx = grid.dims.x(), ny = grid.dims.y(), nz = grid.dims.z();
  if (nx <= 0 || ny <= 0 || nz <= 0)
    fail("cannot write '{}': the grid is empty", file.string());
  AtomicFile atomic(file);
  std::ofstream out(atomic.temp_path(), std::ios::binary);
  const Eigen::Vector3d& o = grid.origin;
  const double h = grid.spacing;
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\">\n"
      << fmt::format("  <ImageData WholeExtent=\"0 {} 0 {} 0 {}\" Origin=\"{:.17g} {:.17g} "
                     "{:.17g}\" Spacing=\"{:.17g} {:.17g} {:.17g}\">\n",
                     nx - 1, ny - 1, nz - 1, o.x(), o.y(), o.z(), h, h, h)
      << fmt::format("    <Piece Extent=\"0 {} 0 {} 0 {}\">\n", nx - 1, ny - 1, nz - 1)
      << fmt::format("      <PointData Scalars=\"{}\">\n", name)
      << fmt::format("        <DataArray type=\"{}\" Name=\"{}\" format=\"appended\" "
                     "offset=\"0\"/>\n",
                     vtk_type_name<T>(), name)
      << "      </PointData>\n      <CellData/>\n    </Piece>\n  </ImageData>\n"
      << "  <AppendedData encoding=\"raw\">\n   _";

  // The compression header (block count, block size, size of a partial last block (0: none),
  // then each block's compressed size) comes first: written as a placeholder, filled at the end.
  const std::streampos header_at = out.tellp();
  const auto slab_values = static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
  const std::size_t slab_bytes = slab_values * sizeof(T);
  if (slab_bytes > std::numeric_limits<uLong>::max() / 2)
    fail("cannot write '{}': a slab of {} x {} voxels is too large", file.string(), nx, ny);
  std::vector<std::uint64_t> compressed_sizes(static_cast<std::size_t>(nz), 0);
  for (std::size_t i = 0; i < 3 + compressed_sizes.size(); ++i)
    write_u64(out, 0);

  std::vector<T> slab(slab_values);
  std::vector<Bytef> packed(compressBound(static_cast<uLong>(slab_bytes)));
  for (int k = 0; k < nz; ++k) {
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        slab[static_cast<std::size_t>(i) + static_cast<std::size_t>(nx) * j] = grid(i, j, k);
    uLongf packed_size = static_cast<uLongf>(packed.size());
    if (compress2(packed.data(), &packed_size, reinterpret_cast<const Bytef*>(slab.data()),
                  static_cast<uLong>(slab_bytes), Z_BEST_SPEED) != Z_OK)
      fail("cannot write '{}': zlib failed on slab {}", file.string(), k);
    out.write(reinterpret_cast<const char*>(packed.data()),
              static_cast<std::streamsize>(packed_size));
    compressed_sizes[static_cast<std::size_t>(k)] = packed_size;
  }
  out << "\n  </AppendedData>\n</VTKFile>\n";
  out.seekp(header_at);
  write_u64(out, compressed_sizes.size());
  write_u64(out, slab_bytes);
  write_u64(out, 0);
  for (std::uint64_t size : compressed_sizes)
    write_u64(out, size);
  out.close();
  if (!out)
    fail("cannot write '{}': write failed (disk full?)", file.string());
  atomic.commit();
}

template void write_vti(const Grid<float>&, const std::string&, const std::filesystem::path&);
template void write_vti(const Grid<std::uint8_t>&, const std::string&,
                        const std::filesystem::path&);

} // namespace ligsim
