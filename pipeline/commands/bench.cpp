#include "pipeline/commands/commands.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "common/run_summary.hpp"
#include "pipeline/stage_graph/build_config.hpp"
#include "pipeline/stage_graph/stage_graph.hpp"
#include "stages/io/surface_reader.hpp"
#include "stages/voxelize/voxelize.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <memory>
#include <sstream>

namespace ligsim::cli {

namespace fs = std::filesystem;

namespace {

struct BenchOptions {
  std::string out;
  std::string source_dir;
};

struct Sample {
  std::string name;
  pipeline::BuildConfig config;
};

/// Every stage of `ligsim build`, rerun from scratch on each sample at the default voxel spacing
/// and at half of it: wall time and peak memory per stage, as CSV and a Markdown table.
void run_bench_build(const BenchOptions& o)
{
  const fs::path out = o.out;
  const fs::path data = fs::path(o.source_dir) / "data";
  ensure_directory(out);

  std::vector<Sample> samples;
  {
    // The synthetic band, written by `ligsim synth band` into the bench folder.
    const fs::path shape = out / "band-shape";
    if (!fs::exists(shape / "surface.stl"))
      fail("'{}' is missing: run `ligsim synth band --out {}` first",
           (shape / "surface.stl").string(), shape.string());
    pipeline::BuildConfig band;
    band.surface = shape / "surface.stl";
    band.femur = shape / "femur.stl";
    band.tibia = shape / "tibia.stl";
    samples.push_back({"synthetic band 80x12x3 mm", band});
    samples.push_back(
        {"VHF right MCL", pipeline::load_build_config(data / "vhf-right-knee" / "mcl.toml")});
  }

  std::ostringstream csv, table;
  csv << "sample,voxel_mm,stage,wall_s,peak_rss_mib\n";
  table
      << "| sample | voxel (mm) | stage | wall (s) | peak memory (MiB) |\n|---|---|---|---|---|\n";
  for (Sample& sample : samples) {
    const double spacing = voxelize::default_spacing(io::read_surface(sample.config.surface));
    for (double factor : {1.0, 0.5}) {
      sample.config.voxelize.spacing_mm = spacing * factor;
      const fs::path dir =
          out / fmt::format("{}-{:.3f}", sample.name.substr(0, 3), spacing * factor);
      log_info(fmt::format("bench: {} at {:.3f} mm", sample.name, spacing * factor));
      RunSummary summary("bench");
      pipeline::run_target(sample.config, dir, "model", true, summary);
      for (const pipeline::Stage& stage : pipeline::build_stages()) {
        const auto& entry = summary.json()["stages"][stage.name];
        const double wall = entry["wall_s"], memory = entry["peak_rss_mib"];
        csv << fmt::format("{},{:.4f},{},{:.3f},{:.1f}\n", sample.name, spacing * factor,
                           stage.name, wall, memory);
        table << fmt::format("| {} | {:.3f} | {} | {:.3f} | {:.1f} |\n", sample.name,
                             spacing * factor, stage.name, wall, memory);
      }
    }
  }
  write_text_atomically(out / "bench-build.csv", csv.str());
  write_text_atomically(out / "bench-build.md", table.str());
  fmt::print("{}", table.str());
}

} // namespace

void add_bench_command(CLI::App& app)
{
  auto* bench = app.add_subcommand("bench", "benchmarks (long: not part of the test suite)");
  bench->require_subcommand(1);
  auto* build = bench->add_subcommand(
      "build", "time and peak memory of every build stage on the synthetic band and the real MCL, "
               "at the default voxel spacing and half of it");
  auto options = std::make_shared<BenchOptions>();
  build->add_option("--out", options->out, "folder for the runs and bench-build.csv / .md")
      ->required();
  build->add_option("--source", options->source_dir, "the ligsim source tree (for data/)")
      ->default_val(".");
  build->callback([options] { run_bench_build(*options); });
}

} // namespace ligsim::cli
