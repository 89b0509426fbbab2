/// pipeline/study/run_errors and study_runs: relative errors per angle, Richardson extrapolation
/// on exact power laws, the volume-weighted quantile.

#include "pipeline/study/csv_text.hpp"
#include "pipeline/study/run_errors.hpp"
#include "pipeline/study/study_runs.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace ligsim::study;

namespace {

AngleFigures angle(double deg, double energy, double mean, double p95, Eigen::Vector3d force,
                   double regional = NAN)
{
  AngleFigures a;
  a.regional_fiber_stretch = regional;
  a.angle_deg = deg;
  a.strain_energy_mj = energy;
  a.mean_fiber_stretch = mean;
  a.p95_fiber_stretch = p95;
  a.max_fiber_stretch = p95 + 0.1;
  a.femur_force_n = force;
  return a;
}

} // namespace

TEST(StudyErrors, RelativeErrorsPerSharedAngle)
{
  FlexionFigures reference, run;
  reference.angles = {angle(0, 100, 1.02, 1.05, {0, 0, 10}, 1.04),
                      angle(45, 200, 1.10, 1.20, {0, 3, 4}, 1.08)};
  run.angles = {angle(0, 110, 1.03, 1.05, {0, 0, 9}, 1.05), angle(30, 1, 1, 1, {1, 0, 0}),
                angle(45, 180, 1.10, 1.25, {0, 4, 4}, 1.07)};
  const std::vector<AngleErrors> errors = angle_errors(run, reference);
  ASSERT_EQ(errors.size(), 2u); // 30 degrees is not in the reference
  EXPECT_DOUBLE_EQ(errors[0].angle_deg, 0.0);
  EXPECT_NEAR(errors[0].error[0], 0.1, 1e-12);       // energy 110 against 100
  EXPECT_NEAR(errors[0].error[1], 0.5, 1e-12);       // strain 0.03 against 0.02
  EXPECT_NEAR(errors[0].error[2], 0.0, 1e-12);       // p95 the same
  EXPECT_NEAR(errors[0].error[3], 0.1, 1e-12);       // |(0,0,-1)| / 10
  EXPECT_NEAR(errors[1].error[0], 0.1, 1e-12);       // 180 against 200
  EXPECT_NEAR(errors[1].error[2], 0.25, 1e-12);      // 0.25 against 0.20
  EXPECT_NEAR(errors[1].error[3], 1.0 / 5.0, 1e-12); // |(0,1,0)| / 5: the direction counts
  EXPECT_NEAR(errors[0].error[4], 0.25, 1e-12);      // regional peak 5 % against 4 %
  EXPECT_NEAR(errors[1].error[4], 0.125, 1e-12);     // 7 % against 8 %
  const auto worst = worst_errors(errors);
  EXPECT_NEAR(worst[1], 0.5, 1e-12);
  EXPECT_NEAR(worst[3], 0.2, 1e-12);
  EXPECT_NEAR(worst[4], 0.25, 1e-12);
  EXPECT_TRUE(std::isnan(worst_errors({})[0]));
  // A run that measured no regional peak has no regional error, not a zero one.
  for (AngleFigures& a : run.angles)
    a.regional_fiber_stretch = NAN;
  EXPECT_TRUE(std::isnan(worst_errors(angle_errors(run, reference))[4]));
  EXPECT_NEAR(worst_errors(angle_errors(run, reference))[0], 0.1, 1e-12);
}

TEST(StudyErrors, RichardsonRecoversAnExactPowerLaw)
{
  for (double p : {1.0, 2.0, 3.5}) {
    const std::array<double, 3> h = {0.9, 0.55, 0.31}; // uneven ratios, as CGAL meshes give
    std::array<double, 3> f{};
    for (int i = 0; i < 3; ++i)
      f[i] = 42.0 - 7.0 * std::pow(h[i], p);
    const auto e = richardson(h, f);
    ASSERT_TRUE(e.has_value()) << p;
    EXPECT_NEAR(e->value, 42.0, 1e-8) << p;
    EXPECT_NEAR(e->order, p, 1e-8) << p;
  }
}

TEST(StudyErrors, RichardsonRefusesWhatIsNotMonotone)
{
  EXPECT_FALSE(richardson({1.0, 0.5, 0.25}, {1.0, 2.0, 1.5}).has_value());  // oscillates
  EXPECT_FALSE(richardson({1.0, 0.5, 0.25}, {1.0, 2.0, 4.0}).has_value());  // diverges
  EXPECT_FALSE(richardson({1.0, 0.5, 0.25}, {1.0, 1.0, 1.0}).has_value());  // no change
  EXPECT_FALSE(richardson({0.25, 0.5, 1.0}, {1.0, 1.5, 1.75}).has_value()); // wrong order of h
}

TEST(StudyErrors, WeightedQuantileCountsVolume)
{
  // One big element with the smallest value holds 90 % of the volume.
  const std::vector<double> values = {3.0, 1.0, 2.0, 4.0};
  const std::vector<double> volumes = {0.05, 9.0, 0.5, 0.45};
  // The smallest value with at least that share of the volume at or below it.
  EXPECT_DOUBLE_EQ(weighted_quantile(values, volumes, 0.5), 1.0);
  EXPECT_DOUBLE_EQ(weighted_quantile(values, volumes, 0.9), 1.0);   // 9 of 10 at 1
  EXPECT_DOUBLE_EQ(weighted_quantile(values, volumes, 0.93), 2.0);  // 9.5 at or below 2
  EXPECT_DOUBLE_EQ(weighted_quantile(values, volumes, 0.954), 3.0); // 9.55 at or below 3
  EXPECT_DOUBLE_EQ(weighted_quantile(values, volumes, 0.96), 4.0);
}

TEST(StudyCsv, TextFieldsAreQuoted)
{
  EXPECT_EQ(csv_quoted("quasi-static, mesh"), "\"quasi-static, mesh\"");
  EXPECT_EQ(csv_quoted("surface 'a' said \"no\""), "\"surface 'a' said \"\"no\"\"\"");
  EXPECT_EQ(csv_quoted(""), "\"\"");
}
