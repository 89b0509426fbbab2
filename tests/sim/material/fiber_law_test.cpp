#include "sim/material/fiber_law.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace ligsim::sim;

namespace {

FiberParameters mcl_fiber(FiberConvention convention)
{
  FiberParameters fiber;
  fiber.convention = convention;
  return fiber;
}

class FiberLawTest : public ::testing::TestWithParam<FiberConvention> {};

} // namespace

TEST_P(FiberLawTest, DerivativesMatchCentralDifferencesInEveryRegime)
{
  const FiberLaw law(mcl_fiber(GetParam()));
  const double h = 1e-6;
  for (double lambda : {0.95, 0.999, 1.001, 1.01, 1.025, 1.031, 1.06, 1.3}) {
    const FiberResponse at = law.evaluate(lambda);
    const FiberResponse plus = law.evaluate(lambda + h);
    const FiberResponse minus = law.evaluate(lambda - h);
    const double d1 = (plus.energy - minus.energy) / (2 * h);
    const double d2 = (plus.d1 - minus.d1) / (2 * h);
    EXPECT_NEAR(d1, at.d1, 1e-6 * std::max(1.0, std::abs(at.d1))) << "lambda " << lambda;
    EXPECT_NEAR(d2, at.d2, 1e-6 * std::max(1.0, std::abs(at.d2))) << "lambda " << lambda;
  }
}

TEST_P(FiberLawTest, ContinuousAtLambdaStarAndZeroWhenSlack)
{
  const FiberLaw law(mcl_fiber(GetParam()));
  const double star = law.parameters().lambda_star;
  const FiberResponse below = law.evaluate(star - 1e-12);
  const FiberResponse above = law.evaluate(star);
  EXPECT_NEAR(below.energy, above.energy, 1e-9);
  EXPECT_NEAR(below.d1, above.d1, 1e-8);
  EXPECT_EQ(law.regime(0.99), FiberRegime::slack);
  EXPECT_EQ(law.regime(1.01), FiberRegime::toe);
  EXPECT_EQ(law.regime(1.05), FiberRegime::linear);
  EXPECT_EQ(law.evaluate(0.9).energy, 0.0);
  EXPECT_EQ(law.evaluate(0.9).d1, 0.0);
  EXPECT_EQ(law.evaluate(1.0).energy, 0.0);
}

TEST(FiberLaw, ConventionsDifferByTheFactorLambda)
{
  const FiberLaw paper(mcl_fiber(FiberConvention::paper));
  const FiberLaw weiss(mcl_fiber(FiberConvention::weiss));
  for (double lambda : {1.01, 1.02, 1.05, 1.2})
    EXPECT_NEAR(lambda * weiss.evaluate(lambda).d1, paper.evaluate(lambda).d1, 1e-9);
  // C6 of eq. 14: the toe and linear expressions meet at lambda*.
  const FiberParameters p = mcl_fiber(FiberConvention::paper);
  EXPECT_NEAR(paper.c6_mpa(),
              p.c3_mpa * (std::exp(p.c4 * (p.lambda_star - 1)) - 1) - p.c5_mpa * p.lambda_star,
              1e-9);
}

TEST(FiberLaw, WeissToeEnergyMatchesTheExponentialIntegral)
{
  // F_C = C3 [exp(-C4) (Ei(C4 lambda) - Ei(C4)) - ln lambda] in the toe region.
  const FiberParameters p = mcl_fiber(FiberConvention::weiss);
  const FiberLaw law(p);
  for (double lambda : {1.005, 1.02, 1.0299}) {
    const double exact =
        p.c3_mpa *
        (std::exp(-p.c4) * (std::expint(p.c4 * lambda) - std::expint(p.c4)) - std::log(lambda));
    EXPECT_NEAR(law.evaluate(lambda).energy, exact, 1e-10 * std::abs(exact) + 1e-14);
  }
}

INSTANTIATE_TEST_SUITE_P(Conventions, FiberLawTest,
                         ::testing::Values(FiberConvention::paper, FiberConvention::weiss));
