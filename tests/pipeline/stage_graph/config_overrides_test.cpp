/// `--set TABLE.KEY=VALUE` through the build and knee config readers: over the file, alone, over
/// every [[ligament]], and refused with the assignment named; and the material's former key names.

#include "../cli_runner.hpp"

#include "common/error.hpp"
#include "pipeline/stage_graph/build_config.hpp"
#include "pipeline/stage_graph/knee_config.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <string>

using namespace ligsim;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

namespace {

fs::path written(const std::string& name, const std::string& text)
{
  const fs::path folder = test::fresh_folder("config_overrides");
  fs::create_directories(folder);
  std::ofstream(folder / name) << text;
  return folder / name;
}

std::string build_error(const fs::path& file, const std::vector<std::string>& overrides)
{
  try {
    pipeline::load_build_config(file, overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

} // namespace

TEST(ConfigOverrides, SetKeysOverTheFileAndKeepTheRest)
{
  const fs::path file =
      written("mcl.toml", "[input]\nsurface = \"mcl.stl\"\n\n[tetmesh]\ncell_size_mm = 2.4\n"
                          "facet_size_mm = 2.4\n");
  const pipeline::BuildConfig config = pipeline::load_build_config(
      file, {"tetmesh.cell_size_mm=1.2", "centerline.span=attachments", "material.c4=120"});
  EXPECT_EQ(config.tetmesh.cell_size_mm, 1.2);
  EXPECT_EQ(config.tetmesh.facet_size_mm, 2.4);
  EXPECT_EQ(config.centerline.span, centerline::Span::attachments);
  EXPECT_EQ(config.material.fiber->c4, 120.0);
  EXPECT_EQ(config.surface, file.parent_path() / "mcl.stl");
  // A section set on the command line counts as given, as in the file.
  EXPECT_EQ(config.given.count("material"), 1u);
}

TEST(ConfigOverrides, BuildWithoutAFileFromTheSettingsAlone)
{
  const pipeline::BuildConfig config = pipeline::load_build_config({}, {"tetmesh.order=2"});
  EXPECT_EQ(config.tetmesh.order, 2);
  EXPECT_EQ(config.voxelize.spacing_mm, pipeline::BuildConfig{}.voxelize.spacing_mm);
}

TEST(ConfigOverrides, OverAKneeTheySetEveryLigament)
{
  const fs::path file = written(
      "knee.toml",
      "[input]\nfemur = \"femur.stl\"\ntibia = \"tibia.stl\"\n\n"
      "[[ligament]]\nname = \"MCL\"\n[ligament.input]\nsurface = \"mcl.stl\"\n\n"
      "[[ligament]]\nname = \"ACL\"\n[ligament.input]\nsurface = \"acl.stl\"\n[ligament.tetmesh]\n"
      "order = 1\ncell_size_mm = 1.0\n");
  const pipeline::KneeConfig knee =
      pipeline::load_knee_config(file, {"ligament.tetmesh.order=2", "voxelize.spacing_mm=0.3"});
  ASSERT_EQ(knee.ligaments.size(), 2u);
  for (const pipeline::LigamentConfig& ligament : knee.ligaments) {
    EXPECT_EQ(ligament.build.tetmesh.order, 2) << ligament.name;
    EXPECT_EQ(ligament.build.voxelize.spacing_mm, 0.3) << ligament.name;
  }
  EXPECT_EQ(knee.ligaments[1].build.tetmesh.cell_size_mm, 1.0);
}

TEST(ConfigOverrides, MistakesNameTheAssignment)
{
  const fs::path file = written("band.toml", "[tetmesh]\ncell_size_mm = 2.4\n");
  EXPECT_THAT(build_error(file, {"tetmesh.cel_size_mm=1.2"}),
              HasSubstr("--set tetmesh.cel_size_mm=1.2: unknown key 'cel_size_mm'"));
  EXPECT_THAT(build_error(file, {"tetmesh.cell_size_mm=fine"}),
              HasSubstr("--set tetmesh.cell_size_mm=fine"));
  EXPECT_THAT(build_error(file, {"tetmsh.order=2"}), HasSubstr("tetmsh"));
  EXPECT_THAT(build_error(file, {"tetmesh.order"}), HasSubstr("expected TABLE.KEY=VALUE"));
  // The material's enumerated keys are checked where they are read, not when a scene runs.
  EXPECT_THAT(build_error(file, {"material.convention=wiess"}),
              HasSubstr("convention: expected \"paper\" or \"weiss\", got \"wiess\""));
  // Without a file, the messages about a table as a whole name the settings too.
  EXPECT_THAT(build_error({}, {"anatomy.side=up"}),
              HasSubstr("--set: [anatomy] side must be \"left\" or \"right\""));
}

TEST(ConfigOverrides, TheMaterialsFormerKeyNamesAreReadAsItsKeys)
{
  // [material] bulk_modulus_mpa and fiber_convention, as build configs named k_mpa and
  // convention, in the file and by --set, and over every ligament of a knee.
  const fs::path file = written("mcl.toml", "[material]\nbulk_modulus_mpa = 500\n");
  const pipeline::BuildConfig config =
      pipeline::load_build_config(file, {"material.fiber_convention=weiss"});
  EXPECT_EQ(config.material.bulk_modulus_mpa, 500.0);
  EXPECT_EQ(config.material.fiber->convention, sim::FiberConvention::weiss);
  // Both names at once: which one is meant is not guessed.
  EXPECT_THAT(build_error(file, {"material.k_mpa=700"}),
              HasSubstr("bulk_modulus_mpa: the former name of k_mpa, which the table gives too"));
  const fs::path knee =
      written("knee.toml", "[input]\nfemur = \"femur.stl\"\ntibia = \"tibia.stl\"\n\n[[ligament]]\n"
                           "name = \"MCL\"\n[ligament.input]\nsurface = \"mcl.stl\"\n"
                           "[ligament.material]\nbulk_modulus_mpa = 600\n");
  EXPECT_EQ(pipeline::load_knee_config(knee).ligaments[0].build.material.bulk_modulus_mpa, 600.0);
}
