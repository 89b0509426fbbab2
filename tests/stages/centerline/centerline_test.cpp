#include "common/error.hpp"
#include "stages/centerline/centerline.hpp"
#include "tests/stages/shape_fixture.hpp"

#include <gtest/gtest.h>

using namespace ligsim;

namespace {

centerline::Centerline extract(const test::VoxelisedShape& v, double alpha, double u0 = 0.02,
                               double u1 = 0.98, bool refine = true, bool extend = true)
{
  centerline::Parameters parameters;
  parameters.alpha = alpha;
  parameters.refine = refine;
  parameters.extend_to_surface = extend;
  return centerline::extract(v.mask, v.distance, test::as_points(v.shape.axis.point(u0)),
                             test::as_points(v.shape.axis.point(u1)), parameters);
}

/// Largest distance from the true axis over the points farther than `margin` mm from both ends.
double max_deviation(const centerline::Centerline& line, const synthetic::Axis& axis, double margin)
{
  double worst = 0.0;
  for (Eigen::Index i = 0; i < line.points.rows(); ++i) {
    double u = 0.0;
    const double d = test::distance_to_axis(axis, line.points.row(i).transpose(), &u);
    if (u * axis.length_mm > margin && (1 - u) * axis.length_mm > margin)
      worst = std::max(worst, d);
  }
  return worst;
}

Eigen::Matrix3d oblique()
{
  return Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 2, 0.5).normalized()).toRotationMatrix();
}

} // namespace

TEST(Centerline, MedialPathOnACylinderFollowsTheAxis)
{
  for (const Eigen::Matrix3d& rotation :
       {Eigen::Matrix3d(Eigen::Matrix3d::Identity()), oblique()}) {
    const auto v = test::voxelise(
        test::transformed(synthetic::cylinder(3.0, 30.0), rotation, {0.11, 0.07, 0.0}), 0.4);
    const auto line = extract(v, 1.0);
    const double deviation = max_deviation(line, v.shape.axis, 3.0);
    RecordProperty(rotation.isIdentity() ? "aligned_max_deviation_mm" : "oblique_max_deviation_mm",
                   std::to_string(deviation));
    EXPECT_LE(deviation, v.mask.spacing);
  }
}

TEST(Centerline, MedialPathOnATorusTubeFollowsTheArc)
{
  const auto v = test::voxelise(synthetic::torus_tube(20.0, 3.0, 120.0), 0.4);
  const auto line = extract(v, 1.0);
  const double deviation = max_deviation(line, v.shape.axis, 3.0);
  RecordProperty("max_deviation_mm", std::to_string(deviation));
  EXPECT_LE(deviation, v.mask.spacing);
  // The tangent follows the arc's tangent.
  double worst_deg = 0.0;
  for (Eigen::Index i = 2; i + 2 < line.points.rows(); ++i) {
    double u = 0.0;
    test::distance_to_axis(v.shape.axis, line.points.row(i).transpose(), &u);
    const double c = std::abs(line.tangents.row(i).dot(v.shape.axis.tangent(u)));
    worst_deg = std::max(worst_deg, std::acos(std::min(1.0, c)) * 180 / 3.14159265358979);
  }
  RecordProperty("worst_tangent_deg", std::to_string(worst_deg));
  EXPECT_LT(worst_deg, 5.0);
}

TEST(Centerline, ShortestPathOnACylinderIsTheStraightSegment)
{
  // alpha = 0: the straight line through the end points (extended to the caps), on a
  // grid-aligned and an oblique axis.
  for (const Eigen::Matrix3d& rotation :
       {Eigen::Matrix3d(Eigen::Matrix3d::Identity()), oblique()}) {
    const auto v =
        test::voxelise(test::transformed(synthetic::cylinder(3.0, 30.0), rotation, {0, 0, 0}), 0.4);
    const Eigen::Vector3d a = v.shape.axis.point(0.02), b = v.shape.axis.point(0.98);
    const auto line = extract(v, 0.0);
    double worst = 0.0;
    for (Eigen::Index i = 0; i < line.points.rows(); ++i) {
      const Eigen::Vector3d p = line.points.row(i);
      const double s = (p - a).dot(b - a) / (b - a).squaredNorm();
      worst = std::max(worst, (p - (a + s * (b - a))).norm());
    }
    RecordProperty(rotation.isIdentity() ? "aligned_max_deviation_mm" : "oblique_max_deviation_mm",
                   std::to_string(worst));
    EXPECT_LE(worst, v.mask.spacing);
  }
}

TEST(Centerline, RefinementLowersTheCostOfTheVoxelPath)
{
  const auto v =
      test::voxelise(test::transformed(synthetic::torus_tube(), oblique(), {0, 0, 0}), 0.5);
  const auto raw = extract(v, 0.1, 0.02, 0.98, false, false);
  const auto refined = extract(v, 0.1, 0.02, 0.98, true, false);
  EXPECT_LT(centerline::path_cost(refined.points, v.distance, 0.1),
            centerline::path_cost(raw.points, v.distance, 0.1));
  EXPECT_LT(refined.length_mm, raw.length_mm);
}

TEST(Centerline, DisconnectedAttachmentsAreAClearError)
{
  auto a = synthetic::cylinder(2.0, 10.0, 32);
  auto b = test::transformed(synthetic::cylinder(2.0, 10.0, 32), Eigen::Matrix3d::Identity(),
                             {0, 0, 15});
  TriangleSurface both = a.surface;
  both.V.conservativeResize(a.surface.V.rows() + b.surface.V.rows(), 3);
  both.V.bottomRows(b.surface.V.rows()) = b.surface.V;
  both.F.conservativeResize(a.surface.F.rows() + b.surface.F.rows(), 3);
  both.F.bottomRows(b.surface.F.rows()) =
      b.surface.F.array() + static_cast<int>(a.surface.V.rows());
  a.surface = both;
  const auto v = test::voxelise(std::move(a), 0.4);
  try {
    centerline::extract(v.mask, v.distance, test::as_points({0, 0, 2}), test::as_points({0, 0, 23}),
                        {});
    FAIL() << "disconnected parts connected";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot be connected"), std::string::npos) << e.what();
  }
}

TEST(Centerline, SpanningTheAttachmentsRunsAlongALongInsertion)
{
  // A1: the surface vertices of the first 3 mm of a cylinder; A2: those from 15 to 30 mm, a long
  // insertion. The paper's line stops at A2's mean (z ~ 22.5); spanning runs to its far end.
  const auto v = test::voxelise(synthetic::cylinder(3.0, 30.0), 0.4);
  std::vector<Eigen::Vector3d> a1, a2;
  for (Eigen::Index i = 0; i < v.shape.surface.V.rows(); ++i) {
    const Eigen::Vector3d p = v.shape.surface.V.row(i);
    if (p.z() <= 3.0)
      a1.push_back(p);
    else if (p.z() >= 15.0)
      a2.push_back(p);
  }
  auto points = [](const std::vector<Eigen::Vector3d>& list) {
    Points result(static_cast<Eigen::Index>(list.size()), 3);
    for (std::size_t i = 0; i < list.size(); ++i)
      result.row(static_cast<Eigen::Index>(i)) = list[i].transpose();
    return result;
  };
  centerline::Parameters parameters;
  parameters.alpha = 1.0;
  parameters.extend_to_surface = false;
  const auto means = centerline::extract(v.mask, v.distance, points(a1), points(a2), parameters);
  parameters.span = centerline::Span::attachments;
  const auto spanning = centerline::extract(v.mask, v.distance, points(a1), points(a2), parameters);
  EXPECT_NEAR(means.points(means.points.rows() - 1, 2), 22.5, 1.0);
  EXPECT_GT(spanning.points(spanning.points.rows() - 1, 2), 29.0);
  EXPECT_LT(spanning.points(0, 2), 1.0);
  EXPECT_THROW(centerline::parse_span("ends"), InputError);
}
