// The flexion stability suite's small cases on a coarse build of the shipped MCL (the ctest
// fixture flexion_stability_model makes it): each converges with the state in equilibrium or
// stops with a diagnostic naming where, and no file gets a non-finite value. `ligsim verify
// stability --suite flexion` runs the whole suite (docs/validation.md, "Stability").

#include "common/error.hpp"
#include "common/progress.hpp"
#include "common/vtk_files.hpp"
#include "sim/flexion/flexion_config.hpp"
#include "sim/mesh/structured_mesh.hpp"
#include "sim/verify/flexion_stability.hpp"

#include <gtest/gtest.h>
#include <vtkDoubleArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

using namespace ligsim::sim;
namespace fs = std::filesystem;

namespace {

fs::path output_folder(const std::string& name)
{
  const fs::path dir = fs::temp_directory_path() / ("ligsim_flexion_stability_" + name);
  fs::remove_all(dir);
  return dir;
}

/// The flexion config's axis and material, three angles to 140 degrees.
FlexionStabilitySuite small_suite()
{
  ligsim::Progress::set_quiet(true);
  FlexionSettings base;
  read_flexion_config(fs::path(LIGSIM_SOURCE_DIR) / "data/vhf-right-knee/flexion.toml", base);
  return FlexionStabilitySuite(base, LIGSIM_FLEXION_TEST_MODEL, {}, {0, 70, 140});
}

class FlexionStability : public ::testing::TestWithParam<std::string> {};

} // namespace

TEST_P(FlexionStability, ConvergesInEquilibriumOrStopsWithADiagnostic)
{
  FlexionStabilitySuite suite = small_suite();
  const FlexionCaseResult result = suite.run(GetParam(), output_folder(GetParam()));
  EXPECT_TRUE(result.non_finite.empty()) << result.non_finite;
  EXPECT_NE(result.outcome, ligsim::sim::Outcome::failed) << result.diagnostic;
  if (result.outcome == ligsim::sim::Outcome::diagnostic)
    return; // names the angle and the step, the element or node (checked by the suite)
  ASSERT_FALSE(result.angles.empty());
  EXPECT_EQ(result.angles.back().angle_deg, 140.0);
  EXPECT_GT(result.min_j, 0.0);
  EXPECT_TRUE(std::isfinite(result.max_fiber_strain));
  if (result.outcome == ligsim::sim::Outcome::converged) {
    // Recomputed from the final states, apart from the solver's own figure.
    EXPECT_LT(result.equilibrium_residual, 1e-6);
  } else {
    EXPECT_EQ(result.outcome, ligsim::sim::Outcome::completed);
  }
}

INSTANTIATE_TEST_SUITE_P(Coarse, FlexionStability,
                         ::testing::Values("coarse_140", "in_situ_10pct", "k_1e2", "c5_x10",
                                           "slivers", "fibers_turned_90", "interactive_dt_1e-1"));

TEST(FlexionStability, ReversedFibersChangeNothing)
{
  // The fiber law depends on a (x) a: turning a fiber end for end is no change at all.
  FlexionStabilitySuite suite = small_suite();
  const FlexionCaseResult plain = suite.run("coarse_140", output_folder("plain"));
  const FlexionCaseResult reversed = suite.run("fibers_reversed", output_folder("reversed"));
  ASSERT_EQ(plain.outcome, ligsim::sim::Outcome::converged) << plain.diagnostic;
  ASSERT_EQ(reversed.outcome, ligsim::sim::Outcome::converged) << reversed.diagnostic;
  ASSERT_EQ(plain.angles.size(), reversed.angles.size());
  for (std::size_t i = 0; i < plain.angles.size(); ++i)
    EXPECT_NEAR(reversed.angles[i].strain_energy_mj, plain.angles[i].strain_energy_mj,
                1e-7 * plain.angles[i].strain_energy_mj);
}

TEST(FlexionStability, FineCasesAreSkippedWithoutAFineModel)
{
  FlexionStabilitySuite suite = small_suite();
  const FlexionCaseResult result = suite.run("fine_140", output_folder("fine"));
  EXPECT_EQ(result.outcome, ligsim::sim::Outcome::skipped);
  EXPECT_THROW(suite.run("no_such_case", output_folder("none")), ligsim::InputError);
}

TEST(FlexionStability, InjectedSliversKeepEveryElementPositive)
{
  ligsim::TetMesh mesh = structured_cube_mesh(4, 1.0);
  const ligsim::TetMesh before = mesh;
  const int made = inject_slivers(mesh, 10, 0.01, {});
  EXPECT_EQ(made, 10);
  int flattened = 0;
  for (Eigen::Index e = 0; e < mesh.T.rows(); ++e) {
    auto volume = [&](const ligsim::TetMesh& m) {
      const Eigen::Vector3d a = m.V.row(m.T(e, 0));
      return (Eigen::Vector3d(m.V.row(m.T(e, 1))) - a)
          .dot((Eigen::Vector3d(m.V.row(m.T(e, 2))) - a)
                   .cross(Eigen::Vector3d(m.V.row(m.T(e, 3))) - a));
    };
    EXPECT_GT(volume(mesh), 0.0) << "element " << e;
    flattened += volume(mesh) < 0.02 * volume(before) ? 1 : 0;
  }
  EXPECT_GE(flattened, made);
}

TEST(FlexionStability, NonFiniteValuesInWrittenFilesAreFound)
{
  const fs::path dir = output_folder("non_finite");
  fs::create_directories(dir);
  auto surface = vtkSmartPointer<vtkPolyData>::New();
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->InsertNextPoint(0, 0, 0);
  points->InsertNextPoint(1, 0, 0);
  surface->SetPoints(points);
  auto gap = vtkSmartPointer<vtkDoubleArray>::New();
  gap->SetName("gap_mm");
  gap->InsertNextValue(0.5);
  gap->InsertNextValue(0.25);
  surface->GetPointData()->AddArray(gap);
  ligsim::write_vtk(surface, dir / "bone.vtp");
  std::ofstream(dir / "table.csv") << "angle,energy\n0,1.5\n";
  EXPECT_FALSE(first_non_finite_value(dir).has_value());

  gap->SetValue(1, std::numeric_limits<double>::quiet_NaN());
  ligsim::write_vtk(surface, dir / "bone.vtp");
  const std::optional<std::string> found = first_non_finite_value(dir);
  ASSERT_TRUE(found.has_value());
  EXPECT_NE(found->find("bone.vtp"), std::string::npos) << *found;
  EXPECT_NE(found->find("gap_mm"), std::string::npos) << *found;

  fs::remove(dir / "bone.vtp");
  std::ofstream(dir / "table.csv") << "angle,energy\n0,-nan\n";
  ASSERT_TRUE(first_non_finite_value(dir).has_value());
  EXPECT_NE(first_non_finite_value(dir)->find("table.csv"), std::string::npos);
}
