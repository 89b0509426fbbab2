#include "sim/membrane/scene/scene.hpp"

#include "common/error.hpp"
#include "sim/membrane/scene/tear_simulation.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace ligsim::membrane {
namespace {

namespace fs = std::filesystem;

class MembraneSceneFile : public ::testing::Test {
protected:
  void SetUp() override
  {
    m_dir = fs::temp_directory_path() /
            ("ligsim_scene_test_" +
             std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::create_directories(m_dir);
    std::ifstream in(fs::path(LIGSIM_SOURCE_DIR) / "data" / "scenes" / "square-sheet-45.toml");
    m_base.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    ASSERT_FALSE(m_base.empty());
  }
  void TearDown() override { fs::remove_all(m_dir); }

  /// Writes the base scene with `from` replaced by `to`; returns its path.
  fs::path variant(const std::string& from, const std::string& to)
  {
    std::string text = m_base;
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos)
      text.replace(at, from.size(), to);
    const fs::path file = m_dir / "scene.toml";
    std::ofstream(file) << text;
    return file;
  }

  /// The message of the InputError that loading (and building) `file` throws.
  static std::string error_of(const fs::path& file)
  {
    try {
      TearSimulation simulation(load_scene(file));
    } catch (const InputError& error) {
      return error.what();
    }
    return "no error";
  }

  fs::path m_dir;
  std::string m_base;
};

TEST_F(MembraneSceneFile, ShippedScenesLoad)
{
  for (const char* name :
       {"square-sheet-0", "square-sheet-45", "square-sheet-90", "capsulorhexis"}) {
    const Scene scene =
        load_scene(fs::path(LIGSIM_SOURCE_DIR) / "data" / "scenes" / (std::string(name) + ".toml"));
    EXPECT_EQ(scene.name, name);
  }
}

TEST_F(MembraneSceneFile, ErrorsNameTheFileAndTheProblem)
{
  EXPECT_NE(error_of(m_dir / "missing.toml").find("missing.toml does not exist"),
            std::string::npos);
  const std::string typo = error_of(variant("fiber_modulus_mpa", "fibre_modulus_mpa"));
  EXPECT_NE(typo.find("unknown key 'fibre_modulus_mpa' in [material]"), std::string::npos) << typo;
  EXPECT_NE(typo.find("scene.toml"), std::string::npos) << typo;
  const std::string syntax = error_of(variant("[mesh]", "[mesh"));
  EXPECT_NE(syntax.find("scene.toml:"), std::string::npos) << syntax;
  EXPECT_NE(error_of(variant("shape = \"rectangle\"", "shape = \"hexagon\"")).find("shape must be"),
            std::string::npos);
  EXPECT_NE(
      error_of(variant("fiber_poisson = 0.45", "fiber_poisson = 3.0")).find("positive definite"),
      std::string::npos);
  EXPECT_NE(error_of(variant("max_turn_deg = 45.0", "max_turn_deg = 270.0")).find("max_turn_deg"),
            std::string::npos);
  EXPECT_NE(
      error_of(variant("box_mm = [-5.01, -5.01, -4.99, 5.01]", "box_mm = [-9.0, -9.0, -8.0, -8.0]"))
          .find("[[traction]] #1 contains no boundary side"),
      std::string::npos);
  EXPECT_NE(error_of(variant("time_step_s = 1e-3", "time_step_s = -1.0")).find("time_step_s"),
            std::string::npos);
  // An integer beyond 2^53 is a number (it was "must be a finite number"); the range check names
  // it.
  const std::string big =
      error_of(variant("max_turn_deg = 45.0", "max_turn_deg = 9007199254740993"));
  EXPECT_NE(big.find("max_turn_deg"), std::string::npos) << big;
  EXPECT_EQ(big.find("finite number"), std::string::npos) << big;
  EXPECT_NE(
      error_of(variant("min_angle_deg = 10.0", "min_angle_deg = 25.0")).find("below min_angle_deg"),
      std::string::npos);
}

TEST_F(MembraneSceneFile, PerElementFibersMustMatchTheMesh)
{
  std::ofstream(m_dir / "fibers.txt") << "10 20 30\n";
  const fs::path file = variant("kind = \"uniform\"\nangle_deg = 45.0",
                                "kind = \"per_element\"\npath = \"fibers.txt\"");
  EXPECT_NE(error_of(file).find("holds 3 angles but the mesh has"), std::string::npos)
      << error_of(file);
  std::ofstream(m_dir / "fibers.txt") << "10 twenty\n";
  EXPECT_NE(error_of(file).find("'twenty'"), std::string::npos);
}

} // namespace
} // namespace ligsim::membrane
