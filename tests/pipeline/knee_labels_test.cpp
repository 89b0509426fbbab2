/// `ligsim build` of a knee whose surfaces come from one segmentation label map: the synthetic
/// knee (femur, tibia, fibula boxes; ligament A on the tibia, C on the fibula) voxelized by
/// `ligsim labelmap`, each part named by its label. Every ligament is taken from its own label
/// into its folder, the bones once into the knee's; bad label configs are refused before
/// anything is written.

#include "stages/geometry/surface_topology.hpp"
#include "stages/io/surface_reader.hpp"
#include "stages/io/vtk_convert.hpp"
#include "stages/synthetic/shapes.hpp"
#include "tests/pipeline/cli_runner.hpp"
#include "tests/pipeline/knee_fixture.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

using namespace ligsim;
using namespace ligsim::test;
namespace fs = std::filesystem;

namespace {

constexpr double kRadius = 1.5; ///< the ligaments' radius, mm (16 mm long)

/// The surfaces and their label map knee.nrrd (labels femur 1, tibia 2, fibula 3, A 4, C 5) in
/// a folder of their own (made once per test process).
const fs::path& labelled_knee()
{
  static const fs::path dir = [] {
    const fs::path d = fresh_folder("knee_labels_" + std::to_string(::getpid()));
    fs::create_directories(d);
    write_knee_bones(d);
    write_straight_ligament(kRadius, -6.0, d / "A.vtp");
    write_straight_ligament(kRadius, 13.0, d / "C.vtp");
    write_vtk(io::to_polydata(synthetic::box({-16, -11, -15}, {17, 11, 31})), d / "around.vtp");
    const CliResult made = run_ligsim(
        "labelmap --spacing 0.3 0.3 0.3 --margin 1 --around " + (d / "around.vtp").string() +
        " --part " + (d / "femur.vtp:1:femur").string() + " --part " +
        (d / "tibia.vtp:2:tibia").string() + " --part " + (d / "fibula.vtp:3:fibula").string() +
        " --part " + (d / "A.vtp:4:A").string() + " --part " + (d / "C.vtp:5:C").string() +
        " --out " + (d / "knee.nrrd").string());
    if (made.exit_code != 0)
      throw std::runtime_error("ligsim labelmap failed: " + made.stderr_text);
    return d;
  }();
  return dir;
}

std::string ligament(const std::string& name, const std::string& distal, const std::string& input)
{
  return "[[ligament]]\nname = \"" + name + "\"\n[ligament.input]\n" + input +
         "\n[ligament.attachments.femur]\nrule = \"end\"\nend = \"proximal\"\n"
         "end_length_mm = 2.0\n[ligament.attachments." +
         distal + "]\nrule = \"end\"\nend = \"distal\"\nend_length_mm = 2.0\n\n";
}

const std::string kInput = "[input]\nlabels = \"knee.nrrd\"\nfemur_label = \"femur\"\n"
                           "tibia_label = \"tibia\"\nfibula_label = \"fibula\"\n\n"
                           "[anatomy]\nproximal = [0, 0, 1]\nposterior = [0, 1, 0]\n\n"
                           "[voxelize]\nspacing_mm = 0.3\n\n[tetmesh]\ncell_size_mm = 1.0\n\n";

/// Runs `ligsim build` on `text` written as knee.toml beside the label map.
CliResult build(const std::string& text, const fs::path& out)
{
  const fs::path dir = fresh_folder("knee_labels_config");
  fs::copy(labelled_knee(), dir, fs::copy_options::recursive);
  std::ofstream(dir / "knee.toml") << text;
  return run_ligsim("build --config " + (dir / "knee.toml").string() + " --out " + out.string());
}

} // namespace

TEST(KneeLabels, EveryLigamentComesFromItsLabelAndTheBonesOnce)
{
  const fs::path out = fresh_folder("knee_labels_out");
  const CliResult built = build(
      kInput + ligament("A", "tibia", "label = \"A\"") + ligament("C", "fibula", "label = 5"), out);
  ASSERT_EQ(built.exit_code, 0) << built.stderr_text;

  const nlohmann::json manifest = read_json(out / "knee.json");
  EXPECT_EQ(manifest["ligaments"].size(), 2u);
  for (const char* bone : {"femur", "tibia", "fibula"})
    EXPECT_TRUE(fs::exists(out / (std::string("labels_") + bone + ".vtp"))) << bone;
  const nlohmann::json report = read_json(out / "summary.json")["results"]["label_map"];
  EXPECT_EQ(report["ligament A"]["label"], 4);
  EXPECT_EQ(report["ligament C"]["label"], 5);
  EXPECT_EQ(report["fibula"]["shells"], 1);

  // Each ligament's surface is its own cylinder (volume within the voxels' error), not another.
  const double cylinder = M_PI * kRadius * kRadius * 16.0;
  for (const auto& [name, x] : {std::pair{"A", -6.0}, std::pair{"C", 13.0}}) {
    const TriangleSurface surface = io::read_surface(out / name / "labels_ligament.vtp");
    EXPECT_NEAR(std::abs(signed_volume(surface)), cylinder, 0.15 * cylinder) << name;
    EXPECT_NEAR(surface.V.col(0).mean(), x, 0.2) << name;
    EXPECT_TRUE(fs::exists(out / name / "model.vtu")) << name;
  }
  // C's distal footprint is bound to the fibula the map gave.
  EXPECT_EQ(read_json(out / "C" / "summary.json")["inputs"]["fibula"],
            (out / "labels_fibula.vtp").string());
}

TEST(KneeLabels, BadLabelConfigsAreRefusedBeforeAnythingIsWritten)
{
  const auto expect_rejected = [](const std::string& text, const std::string& expected) {
    const fs::path out = fresh_folder("knee_labels_bad_out");
    const CliResult result = build(text, out);
    EXPECT_NE(result.exit_code, 0) << text;
    EXPECT_NE(result.stderr_text.find(expected), std::string::npos) << result.stderr_text;
    EXPECT_FALSE(fs::exists(out)) << text;
  };
  const std::string a = ligament("A", "tibia", "label = \"A\"");
  expect_rejected(kInput + ligament("A", "tibia", "label = \"ACL\""), "label map '");
  expect_rejected(kInput + ligament("A", "tibia", "label = \"ACL\""), "ligament A");
  expect_rejected(kInput + ligament("A", "tibia", "surface = \"A.vtp\""),
                  "give its [ligament.input] label");
  expect_rejected("[input]\nfemur = \"femur.vtp\"\ntibia = \"tibia.vtp\"\n" + a,
                  "gives no label map");
  expect_rejected("[input]\nlabels = \"knee.nrrd\"\nfemur_label = \"femur\"\n" + a,
                  "needs the tibia's label");
  expect_rejected(std::string("[input]\nlabels = \"knee.nrrd\"\nfemur = \"femur.vtp\"\n") +
                      "tibia_label = 2\nfemur_label = 1\n" + a,
                  "instead of their files");
  expect_rejected(kInput.substr(0, kInput.find("fibula_label")) + "\n" +
                      ligament("C", "fibula", "label = 5"),
                  "attaches to the fibula, but [input] gives no fibula");
}
