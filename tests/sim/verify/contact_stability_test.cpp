// The contact rows of `verify stability`: a rigid sphere moved 2 mm into a band at once with
// d_hat from 0.01 to 1 mm converges with balanced forces and no node inside; nodes that start
// inside are pushed out, or stop the solve with a diagnostic when they lie too deep.

#include "sim/verify/contact_stability.hpp"

#include <gtest/gtest.h>

#include <string>

using namespace ligsim::sim;

namespace {

class ContactStability : public ::testing::TestWithParam<std::string> {};

} // namespace

TEST_P(ContactStability, ConvergesOrStopsWithADiagnostic)
{
  const std::optional<StabilityResult> result = run_contact_stability_case(GetParam());
  ASSERT_TRUE(result.has_value());
  if (result->name == "contact_node_deep_inside_bone") {
    EXPECT_EQ(result->outcome, ligsim::sim::Outcome::diagnostic);
    EXPECT_NE(result->diagnostic.find("contact obstacle"), std::string::npos) << result->diagnostic;
  } else {
    // "converged" includes: reactions and contact force balance to 1e-6, no node deeper than
    // 0.05 mm inside the exact sphere.
    EXPECT_EQ(result->outcome, ligsim::sim::Outcome::converged) << result->diagnostic;
    EXPECT_LT(result->balance_error, 1e-6);
    EXPECT_GT(result->min_j, 0.0);
  }
}

INSTANTIATE_TEST_SUITE_P(Suite, ContactStability,
                         ::testing::Values("contact_push_2mm_d_hat_0.01",
                                           "contact_push_2mm_d_hat_0.1", "contact_push_2mm_d_hat_1",
                                           "contact_node_inside_bone",
                                           "contact_node_deep_inside_bone"),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param;
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c)))
                               c = '_';
                           return name;
                         });

TEST(ContactStability, RowsAreListedInVerifyStability)
{
  const std::vector<StabilityCase> all = stability_cases();
  for (const StabilityCase& contact : contact_stability_cases())
    EXPECT_TRUE(std::any_of(all.begin(), all.end(), [&](const StabilityCase& c) {
      return c.name == contact.name;
    })) << contact.name;
  EXPECT_FALSE(run_contact_stability_case("bulk_modulus_1e+02").has_value());
}
