#include "common/error.hpp"
#include "stages/field/field.hpp"
#include "tests/stages/shape_fixture.hpp"

#include <gtest/gtest.h>

using namespace ligsim;

namespace {
constexpr double R = 3.0, L = 30.0;

test::VoxelisedShape cylinder()
{
  return test::voxelise(synthetic::cylinder(R, L, 128), 0.3);
}
} // namespace

TEST(Field, GeometricIsTheRelativeRadiusOnACylinder)
{
  const auto v = cylinder();
  const Polyline axis = test::axis_polyline(v.shape.axis);
  const auto field = field::diffusion_field(v.mask, axis, v.query, {});
  double worst = 0.0;
  for (std::size_t i = 0; i < v.mask.voxel_count(); ++i) {
    const float d = field.values.at(i);
    ASSERT_GE(d, 0.0f);
    ASSERT_LE(d, 1.0f);
    if (!v.mask.at(i)) {
      EXPECT_EQ(d, 1.0f);
      continue;
    }
    const Eigen::Vector3d p = v.mask.point(i);
    if (p.z() > 0.0 && p.z() < L)
      worst = std::max(worst, std::abs(d - std::hypot(p.x(), p.y()) / R));
  }
  RecordProperty("worst_abs_error", std::to_string(worst));
  EXPECT_LT(worst, 0.005); // the 128-gon's sag is 0.03 %
  EXPECT_EQ(field.rays_missed, 0);
}

TEST(Field, LaplaceIsHarmonicBetweenLineAndBoundary)
{
  const auto v = cylinder();
  const Polyline axis = test::axis_polyline(v.shape.axis);
  field::Parameters parameters;
  parameters.method = field::Method::laplace;
  const auto field = field::diffusion_field(v.mask, axis, v.query, parameters);
  EXPECT_LT(field.residual, 1e-7);
  // Mid-length, D grows with the radius and stays in [0, 1]; like the 2-D solution
  // ln(r / r0) / ln(R / r0) it lies above the geometric r / R in between.
  std::vector<double> sum(11, 0.0), count(11, 0.0);
  for (std::size_t i = 0; i < v.mask.voxel_count(); ++i) {
    if (!v.mask.at(i))
      continue;
    const Eigen::Vector3d p = v.mask.point(i);
    if (std::abs(p.z() - L / 2) > 5.0)
      continue;
    const double r = std::hypot(p.x(), p.y()) / R;
    const int bin = std::min(10, static_cast<int>(r * 10));
    sum[bin] += field.values.at(i);
    count[bin] += 1;
    EXPECT_GE(field.values.at(i), 0.0f);
    EXPECT_LE(field.values.at(i), 1.0f);
  }
  for (int b = 1; b < 9; ++b) {
    ASSERT_GT(count[b], 0);
    EXPECT_GT(sum[b] / count[b], sum[b - 1] / count[b - 1]);
    EXPECT_GT(sum[b] / count[b], (b + 0.5) / 10.0);
  }
}

TEST(Field, UnknownMethodIsAnError)
{
  EXPECT_THROW(field::parse_method("heat"), InputError);
  EXPECT_EQ(field::parse_method("laplace"), field::Method::laplace);
}
