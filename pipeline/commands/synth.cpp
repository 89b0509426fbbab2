#include "pipeline/commands/commands.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "common/vtk_files.hpp"
#include "stages/io/vtk_convert.hpp"
#include "stages/synthetic/shapes.hpp"

#include <CLI/CLI.hpp>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSTLWriter.h>

#include <memory>

namespace ligsim::cli {

namespace fs = std::filesystem;

namespace {

struct SynthOptions {
  std::string shape;
  std::string out;
};

void write_stl(const TriangleSurface& surface, const fs::path& file)
{
  AtomicFile atomic(file);
  auto writer = vtkSmartPointer<vtkSTLWriter>::New();
  writer->SetInputData(io::to_polydata(surface));
  writer->SetFileName(atomic.temp_path().c_str());
  writer->SetFileTypeToBinary();
  if (writer->Write() != 1)
    fail("writing '{}' failed", file.string());
  atomic.commit();
}

void run_synth(const SynthOptions& o)
{
  synthetic::Shape shape;
  if (o.shape == "band")
    shape = synthetic::ligament_band();
  else if (o.shape == "cylinder")
    shape = synthetic::cylinder();
  else if (o.shape == "torus")
    shape = synthetic::torus_tube();
  else
    fail("unknown shape '{}' (use band, cylinder or torus)", o.shape);
  const fs::path out = o.out;
  ensure_directory(out);
  write_stl(shape.surface, out / "surface.stl");
  if (shape.femur)
    write_stl(*shape.femur, out / "femur.stl");
  if (shape.tibia)
    write_stl(*shape.tibia, out / "tibia.stl");
  // The true axis, for comparing centerlines in ParaView.
  const int count = 200;
  Points points(count, 3), tangents(count, 3);
  for (int i = 0; i < count; ++i) {
    const double u = static_cast<double>(i) / (count - 1);
    points.row(i) = shape.axis.point(u).transpose();
    tangents.row(i) = shape.axis.tangent(u).transpose();
  }
  auto axis = io::polyline_to_polydata(points);
  io::add_array(axis->GetPointData(), "tangent", tangents);
  write_vtk(axis, out / "axis.vtp");
  log_info(fmt::format("wrote the {} to {}", o.shape, out.string()));
}

} // namespace

void add_synth_command(CLI::App& app)
{
  auto* command = app.add_subcommand(
      "synth", "write a synthetic shape with a known axis: band (MCL-like, with femur and tibia "
               "proxies), cylinder or torus (tube along a circular arc)");
  auto options = std::make_shared<SynthOptions>();
  command->add_option("shape", options->shape, "band, cylinder or torus")->required();
  command->add_option("--out", options->out, "output folder")->required();
  command->callback([options] { run_synth(*options); });
}

} // namespace ligsim::cli
