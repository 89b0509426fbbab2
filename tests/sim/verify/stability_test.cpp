// Stiff and extreme cases (issue: stability): each converges to a finite, balanced answer or
// stops with a diagnostic naming the element or node and the cause. A 4 x 4 x 4 cube keeps
// this fast; `ligsim verify stability` runs the 8 x 8 x 8 one.

#include "common/error.hpp"
#include "sim/verify/stability.hpp"

#include <gtest/gtest.h>

#include <string>

using namespace ligsim::sim;

namespace {

class Stability : public ::testing::TestWithParam<std::string> {};

} // namespace

TEST_P(Stability, ConvergesOrStopsWithADiagnostic)
{
  const StabilityResult result = run_stability_case(GetParam(), 4);
  EXPECT_NE(result.outcome, ligsim::sim::Outcome::failed) << result.diagnostic;
  const std::string& name = result.name;
  if (name == "inverted_element") {
    EXPECT_EQ(result.outcome, ligsim::sim::Outcome::diagnostic);
    EXPECT_NE(result.diagnostic.find("element 0"), std::string::npos) << result.diagnostic;
    EXPECT_NE(result.diagnostic.find("inverted"), std::string::npos) << result.diagnostic;
  } else if (name == "nan_node") {
    EXPECT_EQ(result.outcome, ligsim::sim::Outcome::diagnostic);
    EXPECT_NE(result.diagnostic.find("node 5"), std::string::npos) << result.diagnostic;
  } else if (name.rfind("dynamic", 0) == 0) {
    EXPECT_EQ(result.outcome, ligsim::sim::Outcome::completed) << result.diagnostic;
    EXPECT_GT(result.min_j, 0.5);
  } else {
    // The straight equilibrium exists at every load (FEBio finds it): converge, balanced.
    EXPECT_EQ(result.outcome, ligsim::sim::Outcome::converged) << result.diagnostic;
    EXPECT_LT(result.balance_error, 1e-6);
    EXPECT_GT(result.min_j, 0.0);
    if (name == "compression_0.20") { // past the sway bifurcation: converged, said unstable
      EXPECT_NE(result.diagnostic.find("unstable equilibrium, past a bifurcation"),
                std::string::npos)
          << result.diagnostic;
    }
    if (name == "compression_0.20_arc_length") { // the path's critical points, named
      EXPECT_EQ(result.diagnostic.rfind("bifurcation at load factor", 0), 0u) << result.diagnostic;
      EXPECT_NE(result.diagnostic.find("negative eigenvalues 0 -> "), std::string::npos)
          << result.diagnostic;
    }
  }
}

TEST(Stability, ArcLengthAndLoadControlReachTheSameCompressedEquilibrium)
{
  const StabilityResult load_control = run_stability_case("compression_0.20", 4);
  const StabilityResult arc_length = run_stability_case("compression_0.20_arc_length", 4);
  ASSERT_EQ(load_control.outcome, ligsim::sim::Outcome::converged);
  ASSERT_EQ(arc_length.outcome, ligsim::sim::Outcome::converged);
  EXPECT_NEAR(arc_length.max_displacement_mm, load_control.max_displacement_mm, 1e-9);
  EXPECT_NEAR(arc_length.min_j, load_control.min_j, 1e-9);
}

INSTANTIATE_TEST_SUITE_P(Suite, Stability,
                         ::testing::Values("bulk_modulus_1e+02", "bulk_modulus_1e+06", "c5_1e+04",
                                           "load_x10", "compression_0.05", "compression_0.20",
                                           "compression_0.20_arc_length", "dynamic_dt_1e-05",
                                           "dynamic_dt_1e+00", "inverted_element", "sliver",
                                           "nan_node"),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param;
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c)))
                               c = '_';
                           return name;
                         });

TEST(Stability, EveryListedCaseRuns)
{
  EXPECT_GE(stability_cases().size(), 15u);
  EXPECT_THROW(run_stability_case("no_such_case"), ligsim::Error);
}
