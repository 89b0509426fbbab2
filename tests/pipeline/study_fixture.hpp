#pragma once
/// The synthetic band as a study input: a build config with quick meshing (no perturbation or
/// sliver exudation) and a quasi-static flexion config to 30 degrees about a fixed axis.

#include "tests/pipeline/cli_runner.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace ligsim::test {

struct StudyBand {
  std::string tag; ///< unique per test process
  std::filesystem::path folder, build_config, flexion_config;

  explicit StudyBand(const std::string& name)
      : tag(name + "_" + std::to_string(::getpid()))
  {
    folder = fresh_folder("study_band_" + tag);
    const CliResult made = run_ligsim("synth band --out " + folder.string());
    EXPECT_EQ(made.exit_code, 0) << made.stderr_text;
    build_config = folder / "band.toml";
    std::ofstream(build_config) << "[input]\nsurface = \"surface.stl\"\nfemur = \"femur.stl\"\n"
                                   "tibia = \"tibia.stl\"\n[voxelize]\nspacing_mm = 0.8\n"
                                   "[tetmesh]\ncell_size_mm = 2.0\nfacet_size_mm = 2.0\n"
                                   "facet_distance_mm = 0.2\nperturb = false\n"
                                   "exude_slivers = false\n";
    flexion_config = folder / "flexion.toml";
    // The band's femoral end lies at z = 80 mm; it turns about x there.
    std::ofstream(flexion_config) << "angles_deg = [0, 30]\nimages = false\n[axis]\n"
                                     "method = \"points\"\nfirst_mm = [0, 0, 80]\n"
                                     "second_mm = [1, 0, 80]\n";
  }
};

} // namespace ligsim::test
