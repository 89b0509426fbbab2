#pragma once
/// Study inputs: the synthetic band (a build config with quick meshing, no perturbation or sliver
/// exudation, and a quasi-static flexion config to 30 degrees about a fixed axis), and a small
/// synthetic knee of two ligaments with a one-ligament config of each.

#include "tests/pipeline/cli_runner.hpp"
#include "tests/pipeline/knee_fixture.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
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

/// Two straight ligaments between a femur box and a tibia box: A (radius 1.5 mm, x = -6) and B
/// (radius 2 mm, x = 6), quickly meshed. `knee_config` builds both; `ligament_configs` holds a
/// one-ligament config of each with the same surface, bones and settings, so that each
/// ligament's figures in the knee are its one-ligament model's. The flexion turns the femur
/// about x through z = 16, 5 mm behind the ligaments: 0 and 30 degrees, quasi-static.
struct StudyKnee {
  std::string tag; ///< unique per test process
  std::filesystem::path folder, knee_config, flexion_config;
  std::map<std::string, std::filesystem::path> ligament_configs;

  explicit StudyKnee(const std::string& name)
      : tag(name + "_" + std::to_string(::getpid()))
  {
    folder = fresh_folder("study_knee_" + tag);
    std::filesystem::create_directories(folder);
    write_knee_bones(folder);
    write_straight_ligament(1.5, -6.0, folder / "A.vtp");
    write_straight_ligament(2.0, 6.0, folder / "B.vtp");
    const std::string shared = "[anatomy]\nproximal = [0, 0, 1]\nposterior = [0, 1, 0]\n\n"
                               "[voxelize]\nspacing_mm = 0.4\n\n[tetmesh]\ncell_size_mm = 1.2\n"
                               "perturb = false\nexude_slivers = false\n\n";
    const auto attachments = [](const std::string& prefix) {
      return "[" + prefix + "attachments.femur]\nrule = \"end\"\nend = \"proximal\"\n" +
             "end_length_mm = 2.0\n[" + prefix +
             "attachments.tibia]\nrule = \"end\"\nend = \"distal\"\nend_length_mm = 2.0\n";
    };
    knee_config = folder / "knee.toml";
    std::ofstream knee(knee_config);
    knee << "[input]\nfemur = \"femur.vtp\"\ntibia = \"tibia.vtp\"\n\n" << shared;
    for (const char* ligament : {"A", "B"}) {
      knee << "[[ligament]]\nname = \"" << ligament << "\"\n[ligament.input]\nsurface = \""
           << ligament << ".vtp\"\n"
           << attachments("ligament.") << "\n";
      ligament_configs[ligament] = folder / (std::string(ligament) + ".toml");
      std::ofstream(ligament_configs[ligament])
          << "[input]\nsurface = \"" << ligament
          << ".vtp\"\nfemur = \"femur.vtp\"\ntibia = \"tibia.vtp\"\n\n"
          << shared << attachments("");
    }
    flexion_config = folder / "flexion.toml";
    std::ofstream(flexion_config) << "angles_deg = [0, 30]\nimages = false\n[axis]\n"
                                     "method = \"points\"\nfirst_mm = [0, -5, 16]\n"
                                     "second_mm = [1, -5, 16]\n";
  }
};

} // namespace ligsim::test
