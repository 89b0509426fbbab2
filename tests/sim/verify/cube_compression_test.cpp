// The compression cases of `verify cube --compression` on a 4^3 cube carrying the reference
// mesh's total load: every one converges to a state in equilibrium (no FEBio solution of them
// ships with the project, so equilibrium is the check), and past the sway bifurcation the
// answer is reported unstable.

#include "sim/verify/cube_compression.hpp"

#include <gtest/gtest.h>

using namespace ligsim::sim;

TEST(CubeCompression, EveryCaseConvergesToAnEquilibrium)
{
  const FebioReference reference = read_febio_reference(LIGSIM_SOURCE_DIR "/data/febio-cube");
  const std::vector<FebioCase> cases = cube_compression_cases(reference);
  ASSERT_EQ(cases.size(), 16u);
  const FebioMesh mesh = structured_cube(4, 1.0);
  const double scale = 289.0 / static_cast<double>(mesh.top_nodes.size());
  NewtonSettings settings;
  settings.load_steps = 1;
  for (FebioCase c : cases) {
    c.force_per_top_node_n *= scale;
    const CubeCaseResult r =
        run_cube_case(mesh, c, CubeEnergy::matched, settings, ligsim::Points(), 1.0);
    ASSERT_TRUE(r.converged) << c.name << ": " << r.failure;
    EXPECT_LT(r.relative_residual, 1e-8) << c.name;
    EXPECT_LT(r.balance_error, 1e-8) << c.name;
    EXPECT_LT(r.avg_top_uz_mm, 0.0) << c.name;
    EXPECT_LT(r.volume_change_pct, 0.0) << c.name;
    if (c.name == "cmp_along_020_lnj") {
      EXPECT_GT(r.negative_eigenvalues, 0) << "the paper's largest load is past the bifurcation";
    }
    if (c.name == "cmp_along_002_lnj") {
      EXPECT_EQ(r.negative_eigenvalues, 0);
    }
  }
}

TEST(CubeCompression, NamesSayDirectionLoadAndLaw)
{
  const FebioReference reference = read_febio_reference(LIGSIM_SOURCE_DIR "/data/febio-cube");
  const std::vector<FebioCase> cases = cube_compression_cases(reference);
  EXPECT_EQ(cases.front().name, "cmp_along_002_lnj");
  EXPECT_EQ(cases.back().name, "cmp_across_020_jm1");
  EXPECT_EQ(cases.back().fiber, Eigen::Vector3d::UnitX());
  EXPECT_DOUBLE_EQ(cases.back().force_per_top_node_n.z(), -0.20);
}
