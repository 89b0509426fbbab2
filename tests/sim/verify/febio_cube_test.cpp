// The paper's cube experiment against FEBio 4.11 on its own mesh, with the energy matched to
// FEBio's: only solver convergence separates two correct codes. Two cases here (the smallest
// and the largest load, both volumetric laws); `ligsim verify cube` runs them all.

#include "common/error.hpp"
#include "sim/verify/cube_verification.hpp"

#include <gtest/gtest.h>

#include <string>

using namespace ligsim::sim;

namespace {

const FebioReference& reference()
{
  static const FebioReference loaded = read_febio_reference(LIGSIM_SOURCE_DIR "/data/febio-cube");
  return loaded;
}

const FebioCase& case_named(const std::string& name)
{
  for (const FebioCase& c : reference().cases)
    if (c.name == name)
      return c;
  throw std::runtime_error("no case " + name);
}

class FebioCube : public ::testing::TestWithParam<std::string> {};

} // namespace

TEST_P(FebioCube, MatchedEnergyReproducesFebio)
{
  const FebioMesh mesh = read_febio_mesh(reference().mesh_file);
  const FebioCase& c = case_named(GetParam());
  const ligsim::Points febio = read_febio_displacements(c.displacements, mesh.mesh.V.rows());
  NewtonSettings settings;
  settings.load_steps = 1;
  const CubeCaseResult result =
      run_cube_case(mesh, c, CubeEnergy::matched, settings, febio, reference().edge_mm);
  ASSERT_TRUE(result.converged) << result.failure;
  EXPECT_LT(result.avg_error_pct, 0.01);
  EXPECT_LT(result.max_error_pct, 0.05);
  EXPECT_LT(result.max_error_all_pct, 0.05);
  // FEBio's own figures for the same solution.
  EXPECT_NEAR(result.avg_top_uz_mm, c.febio.avg_top_uz_mm.value(), 1e-6);
  EXPECT_NEAR(result.volume_change_pct, 100 * c.febio.volume_change_rel.value(), 1e-3);
}

INSTANTIATE_TEST_SUITE_P(SmallestAndLargestLoad, FebioCube,
                         ::testing::Values("par_t002_pen", "par_t020_abq"));

TEST(FebioReference, MissingFilesAreClearErrors)
{
  EXPECT_THROW(read_febio_reference("/nonexistent"), ligsim::InputError);
  EXPECT_THROW(read_febio_mesh("/nonexistent/mesh.txt"), ligsim::InputError);
}
