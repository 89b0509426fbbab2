#include "stages/centerline/centerline.hpp"
#include "stages/fibers/fibers.hpp"
#include "stages/field/field.hpp"
#include "tests/stages/shape_fixture.hpp"

#include <gtest/gtest.h>

using namespace ligsim;

namespace {

constexpr double kDeg = 180.0 / 3.14159265358979323846;

double angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
  return std::acos(std::min(1.0, std::abs(a.normalized().dot(b.normalized())))) * kDeg;
}

/// The whole chain on a shape: centerline (alpha = 1) between the axis ends, field, fibers.
struct Chain {
  test::VoxelisedShape v;
  centerline::Centerline line;
  std::unique_ptr<Polyline> polyline;
  field::Field field;
  TetMesh mesh;
  fibers::Result fibers;
};

Chain run_chain(synthetic::Shape shape, double spacing, field::Method method)
{
  Chain c{test::voxelise(std::move(shape), spacing), {}, {}, {}, {}, {}};
  centerline::Parameters cp;
  cp.alpha = 1.0;
  c.line = centerline::extract(c.v.mask, c.v.distance, test::as_points(c.v.shape.axis.point(0.05)),
                               test::as_points(c.v.shape.axis.point(0.95)), cp);
  c.polyline = std::make_unique<Polyline>(c.line.points, c.line.tangents);
  field::Parameters fp;
  fp.method = method;
  c.field = field::diffusion_field(c.v.mask, *c.polyline, c.v.query, fp);
  c.mesh = test::structured_tets(c.v.mask, 2);
  const fibers::FiberField fiber_field(*c.polyline, c.field.values, c.v.mask);
  c.fibers = fibers::per_tet_directions(c.mesh, fiber_field, {});
  return c;
}

Eigen::Vector3d centroid(const TetMesh& mesh, Eigen::Index t)
{
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int k = 0; k < 4; ++k)
    sum += mesh.V.row(mesh.T(t, k)).transpose();
  return sum / 4;
}

} // namespace

TEST(Fibers, FollowTheAxisOfACylinder)
{
  for (auto method : {field::Method::geometric, field::Method::laplace}) {
    const Chain c = run_chain(synthetic::cylinder(3.0, 30.0, 96), 0.3, method);
    ASSERT_GT(c.mesh.T.rows(), 1000);
    double worst = 0.0;
    for (Eigen::Index t = 0; t < c.mesh.T.rows(); ++t)
      worst = std::max(worst,
                       angle_deg(c.fibers.directions.row(t).transpose(), Eigen::Vector3d::UnitZ()));
    RecordProperty(field::to_string(method) + "_worst_deg", std::to_string(worst));
    EXPECT_LT(worst, 2.0) << field::to_string(method);
  }
}

TEST(Fibers, FollowTheCircleTangentOfATorusTube)
{
  for (auto method : {field::Method::geometric, field::Method::laplace}) {
    const Chain c = run_chain(synthetic::torus_tube(20.0, 3.0, 120.0), 0.3, method);
    double sum = 0.0;
    for (Eigen::Index t = 0; t < c.mesh.T.rows(); ++t) {
      double u = 0.0;
      test::distance_to_axis(c.v.shape.axis, centroid(c.mesh, t), &u);
      sum += angle_deg(c.fibers.directions.row(t).transpose(), c.v.shape.axis.tangent(u));
    }
    RecordProperty(field::to_string(method) + "_mean_deg", std::to_string(sum / c.mesh.T.rows()));
    EXPECT_LT(sum / c.mesh.T.rows(), 5.0) << field::to_string(method);
  }
}

TEST(Fibers, LieOnTheIsosurfacesOfTheField)
{
  const Chain c = run_chain(synthetic::torus_tube(20.0, 3.0, 120.0), 0.4, field::Method::geometric);
  const fibers::FiberField fiber_field(*c.polyline, c.field.values, c.v.mask);
  int checked = 0;
  for (std::size_t i = 0; i < c.v.mask.voxel_count(); i += 3) {
    if (!c.v.mask.at(i))
      continue;
    const auto s = fiber_field.at(c.v.mask.point(i) + Eigen::Vector3d(0.05, 0.1, 0.07));
    if (!s.projected)
      continue;
    EXPECT_NEAR(s.direction.norm(), 1.0, 1e-12);
    EXPECT_LT(std::abs(s.direction.dot(s.gradient.normalized())), 1e-9);
    ++checked;
  }
  EXPECT_GT(checked, 1000);
}
