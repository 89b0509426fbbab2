#include "common/error.hpp"
#include "sim/flexion/axis/condyle_axis.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

using ligsim::InputError;
using ligsim::TriangleSurface;
using ligsim::sim::CondyleAxisFit;
using ligsim::sim::fit_condyle_axis;

namespace {

constexpr double kPi = 3.14159265358979323846;

double degrees(double radians)
{
  return radians * 180.0 / kPi;
}

/// Angle between two vectors, radians (accurate near 0).
double angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

/// Angle between two lines (directions up to sign), radians.
double line_angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
  const double theta = angle(a, b);
  return std::min(theta, kPi - theta);
}

/// Distance of `point` from the line through `on_line` along unit `direction`.
double distance_to_line(const Eigen::Vector3d& point, const Eigen::Vector3d& on_line,
                        const Eigen::Vector3d& direction)
{
  const Eigen::Vector3d w = point - on_line;
  return (w - w.dot(direction) * direction).norm();
}

/// A rigid placement of the local knee frame: local x = the cylinder's axis, y = posterior,
/// z = proximal.
struct Placement {
  Eigen::Matrix3d R;
  Eigen::Vector3d t;
  Eigen::Vector3d proximal() const { return R.col(2); }
  Eigen::Vector3d posterior() const { return R.col(1); }
  /// The true axis with the rule's sign: proximal x posterior.
  Eigen::Vector3d flexion() const { return proximal().cross(posterior()); }
};

Placement tilted_placement()
{
  Placement placement;
  placement.R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, 2.0, 3.0).normalized()) *
                Eigen::AngleAxisd(-1.3, Eigen::Vector3d(0.2, -1.0, 0.4).normalized()) *
                Eigen::Matrix3d::Identity();
  placement.t = Eigen::Vector3d(120.5, -33.25, 540.125);
  return placement;
}

/// Closed "generalised cylinder" about the local x axis: the point at axial position s in
/// [s_min, s_max] and angle theta (0 = distal, pi/2 = posterior, pi = proximal, 3 pi/2 =
/// anterior) lies at distance radius(s, theta) from the axis; flat caps close the ends.
TriangleSurface generalised_cylinder(const std::function<double(double, double)>& radius,
                                     double s_min, double s_max, int rings, int sectors,
                                     const Placement& placement)
{
  TriangleSurface surface;
  surface.V.resize((rings + 1) * sectors + 2, 3);
  const auto place = [&](const Eigen::Vector3d& local) {
    return (placement.R * local + placement.t).transpose();
  };
  for (int j = 0; j <= rings; ++j) {
    const double s = s_min + (s_max - s_min) * j / rings;
    for (int k = 0; k < sectors; ++k) {
      const double theta = 2.0 * kPi * k / sectors;
      const double r = radius(s, theta);
      surface.V.row(j * sectors + k) =
          place(Eigen::Vector3d(s, r * std::sin(theta), -r * std::cos(theta)));
    }
  }
  const int first_cap = (rings + 1) * sectors;
  surface.V.row(first_cap) = place(Eigen::Vector3d(s_min, 0.0, 0.0));
  surface.V.row(first_cap + 1) = place(Eigen::Vector3d(s_max, 0.0, 0.0));
  std::vector<std::array<int, 3>> faces;
  for (int j = 0; j < rings; ++j)
    for (int k = 0; k < sectors; ++k) {
      const int a = j * sectors + k, b = j * sectors + (k + 1) % sectors;
      const int c = a + sectors, d = b + sectors;
      faces.push_back({a, b, d});
      faces.push_back({a, d, c});
    }
  for (int k = 0; k < sectors; ++k) {
    faces.push_back({first_cap, (k + 1) % sectors, k});
    faces.push_back({first_cap + 1, rings * sectors + k, rings * sectors + (k + 1) % sectors});
  }
  surface.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int i = 0; i < 3; ++i)
      surface.F(static_cast<Eigen::Index>(f), i) = faces[f][static_cast<std::size_t>(i)];
  return surface;
}

double signed_volume(const TriangleSurface& surface)
{
  double volume = 0.0;
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f) {
    const Eigen::Vector3d a = surface.V.row(surface.F(f, 0)).transpose();
    const Eigen::Vector3d b = surface.V.row(surface.F(f, 1)).transpose();
    const Eigen::Vector3d c = surface.V.row(surface.F(f, 2)).transpose();
    volume += a.dot(b.cross(c)) / 6.0;
  }
  return volume;
}

/// Smooth window: 1 for x in [a, b], 0 outside [a - ramp, b + ramp], cosine in between.
double window(double x, double a, double b, double ramp)
{
  if (x < a - ramp || x > b + ramp)
    return 0.0;
  if (x < a)
    return 0.5 - 0.5 * std::cos(kPi * (x - (a - ramp)) / ramp);
  if (x > b)
    return 0.5 + 0.5 * std::cos(kPi * (x - b) / ramp);
  return 1.0;
}

/// Two condyles about the local x axis (radii 20.5 mm at s = -20 and 20 mm at s = +20, rounded
/// mediolaterally), an intercondylar notch between them posteriorly and distally, a 3 mm bump
/// (an osteophyte) on the back of the first condyle, and a bulged trochlea with a groove
/// anteriorly; radial noise of 0.15 mm (fixed seed). The least-squares cylinder of two coaxial
/// condyles of unequal radii tilts toward the smaller one, by about 1.5 degrees per mm of
/// difference at this spacing; 0.5 mm keeps that well inside the tests' 2 degrees.
TriangleSurface condyle_pair(const Placement& placement)
{
  const auto radius = [](double s, double theta) {
    const double condyle =
        s < 0.0 ? 20.5 - (s + 20.0) * (s + 20.0) / 60.0 : 20.0 - (s - 20.0) * (s - 20.0) / 60.0;
    const double notch = 8.0 * window(s, -5.0, 5.0, 4.0) * window(theta, 0.0, 2.6, 0.4);
    const double bump = 3.0 * window(s, -22.0, -18.0, 2.0) * window(theta, 1.6, 1.8, 0.2);
    const double trochlea =
        7.0 * window(theta, 3.9, 5.4, 0.5) * (1.0 - 0.4 * std::exp(-(s / 8.0) * (s / 8.0)));
    return condyle - notch + bump + trochlea;
  };
  TriangleSurface surface = generalised_cylinder(radius, -33.0, 33.0, 66, 180, placement);
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 0.15);
  const Eigen::Vector3d axis = placement.R.col(0);
  for (Eigen::Index v = 0; v < surface.V.rows(); ++v) {
    const Eigen::Vector3d w = surface.V.row(v).transpose() - placement.t;
    const Eigen::Vector3d radial = w - w.dot(axis) * axis;
    if (radial.norm() > 1.0)
      surface.V.row(v) += noise(random) * radial.normalized().transpose();
  }
  return surface;
}

/// Binary STL, vertices merged where their coordinates are equal.
TriangleSurface read_binary_stl(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw std::runtime_error("cannot open " + path);
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)),
                                std::istreambuf_iterator<char>());
  std::uint32_t count = 0;
  if (bytes.size() < 84)
    throw std::runtime_error(path + " is too short for a binary STL");
  std::memcpy(&count, bytes.data() + 80, 4);
  if (bytes.size() != 84 + 50 * static_cast<std::size_t>(count))
    throw std::runtime_error(path + " is not a binary STL of " + std::to_string(count) +
                             " triangles");
  std::map<std::array<float, 3>, int> index;
  std::vector<std::array<float, 3>> points;
  TriangleSurface surface;
  surface.F.resize(count, 3);
  for (std::uint32_t f = 0; f < count; ++f)
    for (int i = 0; i < 3; ++i) {
      std::array<float, 3> p;
      std::memcpy(p.data(), bytes.data() + 84 + 50 * static_cast<std::size_t>(f) + 12 + 12 * i, 12);
      const auto [it, inserted] = index.emplace(p, static_cast<int>(points.size()));
      if (inserted)
        points.push_back(p);
      surface.F(f, i) = it->second;
    }
  surface.V.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t v = 0; v < points.size(); ++v)
    for (int a = 0; a < 3; ++a)
      surface.V(static_cast<Eigen::Index>(v), a) = points[v][static_cast<std::size_t>(a)];
  return surface;
}

std::string vhf_file(const std::string& name)
{
  return std::string(LIGSIM_SOURCE_DIR) + "/data/vhf-right-knee/" + name;
}

/// The VHF right knee's anatomical directions in its data frame (see the notch test below and
/// data/vhf-right-knee/README.md): +z proximal, -y posterior, -x medial (the MCL's side).
const Eigen::Vector3d kVhfProximal(0.0, 0.0, 1.0);
const Eigen::Vector3d kVhfPosterior(0.0, -1.0, 0.0);

/// `vector` turned by `degrees` about unit `axis`.
Eigen::Vector3d turned(const Eigen::Vector3d& vector, const Eigen::Vector3d& axis, double deg)
{
  return Eigen::AngleAxisd(deg * kPi / 180.0, axis.normalized()) * vector;
}

} // namespace

TEST(CondyleAxis, RecoversATiltedCylinderExactly)
{
  const Placement placement = tilted_placement();
  const double radius = 20.0;
  const TriangleSurface surface = generalised_cylinder([radius](double, double) { return radius; },
                                                       -30.0, 30.0, 30, 144, placement);
  ASSERT_GT(signed_volume(surface), 0.0);
  // The posterior hint need not be perpendicular to the proximal one.
  const Eigen::Vector3d posterior = placement.posterior() + 0.3 * placement.proximal();
  const CondyleAxisFit fit = fit_condyle_axis(surface, placement.proximal(), posterior);

  EXPECT_LT(angle(fit.axis.direction, placement.flexion()), 1e-6);
  EXPECT_NEAR(fit.axis.direction.norm(), 1.0, 1e-12);
  EXPECT_NEAR(fit.radius_mm, radius, 1e-6);
  EXPECT_LT((fit.axis.point_mm - placement.t).norm(), 1e-6);
  EXPECT_LT(fit.rms_residual_mm, 1e-6);
  EXPECT_EQ(fit.points_used, fit.points_considered);
  EXPECT_GT(fit.points_considered, 100);
  // Rings every 2 mm; the end rings' normals lean onto the caps and drop out: -28 to +28 mm.
  EXPECT_NEAR(fit.span_mm, 56.0, 1e-9);
}

TEST(CondyleAxis, ReversedSurfaceOrientationGivesTheSameFit)
{
  const Placement placement = tilted_placement();
  TriangleSurface surface =
      generalised_cylinder([](double, double) { return 20.0; }, -30.0, 30.0, 30, 144, placement);
  const CondyleAxisFit outward =
      fit_condyle_axis(surface, placement.proximal(), placement.posterior());
  surface.F.col(1).swap(surface.F.col(2));
  ASSERT_LT(signed_volume(surface), 0.0);
  const CondyleAxisFit inward =
      fit_condyle_axis(surface, placement.proximal(), placement.posterior());
  EXPECT_LT(angle(inward.axis.direction, outward.axis.direction), 1e-9);
  EXPECT_NEAR(inward.radius_mm, outward.radius_mm, 1e-9);
  EXPECT_EQ(inward.points_used, outward.points_used);
}

TEST(CondyleAxis, TwoNoisyCondylesAndATrochleaGiveTheAxisWithinTwoDegrees)
{
  const Placement placement = tilted_placement();
  const TriangleSurface surface = condyle_pair(placement);
  const CondyleAxisFit fit = fit_condyle_axis(surface, placement.proximal(), placement.posterior());
  const Eigen::Vector3d truth = placement.flexion();
  const double error_deg = degrees(angle(fit.axis.direction, truth));
  RecordProperty("axis_error_deg", std::to_string(error_deg));
  RecordProperty("radius_mm", std::to_string(fit.radius_mm));
  RecordProperty("rms_residual_mm", std::to_string(fit.rms_residual_mm));
  EXPECT_LT(error_deg, 2.0); // also the sign: proximal x posterior
  EXPECT_GT(fit.axis.direction.dot(placement.proximal().cross(placement.posterior())), 0.0);
  EXPECT_LT(distance_to_line(placement.t, fit.axis.point_mm, fit.axis.direction), 1.0);
  EXPECT_NEAR(fit.radius_mm, 20.0, 1.0);
  EXPECT_LT(fit.rms_residual_mm, 1.0);
  EXPECT_LT(fit.points_used, fit.points_considered); // notch and sides trimmed away

  // The opposite posterior hint reverses the direction (the rule), whatever it then fits.
  const CondyleAxisFit reversed =
      fit_condyle_axis(surface, placement.proximal(), -placement.posterior());
  EXPECT_LT(reversed.axis.direction.dot(fit.axis.direction), 0.0);
  EXPECT_GT(reversed.axis.direction.dot(placement.proximal().cross(-placement.posterior())), 0.0);
}

TEST(CondyleAxis, PosteriorHintTwentyDegreesOffChangesTheAxisByLessThanTwoDegrees)
{
  const Placement placement = tilted_placement();
  const TriangleSurface surface = condyle_pair(placement);
  const CondyleAxisFit reference =
      fit_condyle_axis(surface, placement.proximal(), placement.posterior());
  // The posterior hint turned about the proximal direction (a mediolateral misjudgement), and
  // the proximal hint tilted in the sagittal plane, either way.
  for (const double deg : {-20.0, 20.0}) {
    const CondyleAxisFit turned_back = fit_condyle_axis(
        surface, placement.proximal(), turned(placement.posterior(), placement.proximal(), deg));
    EXPECT_LT(degrees(angle(turned_back.axis.direction, reference.axis.direction)), 2.0)
        << "posterior hint turned " << deg << " degrees about proximal";
    EXPECT_NEAR(turned_back.radius_mm, reference.radius_mm, 0.5);
    const CondyleAxisFit tilted_up = fit_condyle_axis(
        surface, turned(placement.proximal(), placement.R.col(0), deg), placement.posterior());
    EXPECT_LT(degrees(angle(tilted_up.axis.direction, reference.axis.direction)), 2.0)
        << "proximal hint tilted " << deg << " degrees";
  }
}

TEST(CondyleAxis, BadInputsAreInputErrors)
{
  const Placement placement = tilted_placement();
  const TriangleSurface surface =
      generalised_cylinder([](double, double) { return 20.0; }, -30.0, 30.0, 10, 48, placement);
  const Eigen::Vector3d up = placement.proximal(), back = placement.posterior();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(fit_condyle_axis(surface, Eigen::Vector3d::Zero(), back), InputError);
  EXPECT_THROW(fit_condyle_axis(surface, up, Eigen::Vector3d::Zero()), InputError);
  EXPECT_THROW(fit_condyle_axis(surface, up, -2.0 * up), InputError);
  EXPECT_THROW(fit_condyle_axis(surface, up, up + 0.01 * back), InputError);
  EXPECT_THROW(fit_condyle_axis(surface, Eigen::Vector3d(nan, 0, 1), back), InputError);
  EXPECT_THROW(fit_condyle_axis(surface, up, Eigen::Vector3d(0, INFINITY, 0)), InputError);

  TriangleSurface with_nan = surface;
  with_nan.V(7, 1) = nan;
  EXPECT_THROW(fit_condyle_axis(with_nan, up, back), InputError);

  TriangleSurface bad_face = surface;
  bad_face.F(3, 2) = static_cast<int>(surface.V.rows());
  EXPECT_THROW(fit_condyle_axis(bad_face, up, back), InputError);

  TriangleSurface tetrahedron;
  tetrahedron.V.resize(4, 3);
  tetrahedron.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  tetrahedron.F.resize(4, 3);
  tetrahedron.F << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  EXPECT_THROW(fit_condyle_axis(tetrahedron, up, back), InputError);
  EXPECT_THROW(fit_condyle_axis(TriangleSurface{}, up, back), InputError);

  // A flat posterior face is not a condyle: a box.
  const TriangleSurface box = generalised_cylinder(
      [](double, double theta) {
        const double c = std::abs(std::cos(theta)), s = std::abs(std::sin(theta));
        return 20.0 / std::max(c, s);
      },
      -30.0, 30.0, 10, 4 * 40, placement);
  try {
    fit_condyle_axis(box, up, back);
    ADD_FAILURE() << "a box has no condyle, but the fit succeeded";
  } catch (const InputError& error) {
    RecordProperty("box_message", error.what());
  }

  try {
    fit_condyle_axis(surface, up, up);
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("parallel"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

/// The evidence that -y is posterior in the VHF data: the femoral cartilage is a horseshoe
/// whose two arms (the condyles, split by the intercondylar notch) lie toward -y, while the
/// trochlea joins them toward +y. The MCL lies at -x, so -x is medial.
TEST(CondyleAxisVhf, IntercondylarNotchOpensTowardMinusY)
{
  const TriangleSurface cartilage =
      read_binary_stl(vhf_file("VHF_Right_Cartilage_FemurDistal_smooth.stl"));
  const TriangleSurface mcl = read_binary_stl(vhf_file("VHF_Right_Ligament_MCL_smooth.stl"));
  const Eigen::RowVector3d low = cartilage.V.colwise().minCoeff();
  const Eigen::RowVector3d high = cartilage.V.colwise().maxCoeff();
  // Widest empty gap in x (1 mm bins) among the vertices of the first and last fifth in y.
  const auto widest_gap = [&](bool toward_minus_y) {
    const double span = high.y() - low.y();
    std::vector<char> occupied(static_cast<std::size_t>(high.x() - low.x()) + 1, 0);
    for (Eigen::Index v = 0; v < cartilage.V.rows(); ++v) {
      const double y = cartilage.V(v, 1);
      if (toward_minus_y ? y < low.y() + 0.2 * span : y > high.y() - 0.2 * span)
        occupied[static_cast<std::size_t>(cartilage.V(v, 0) - low.x())] = 1;
    }
    const auto first = std::find(occupied.begin(), occupied.end(), 1);
    const auto last = std::find(occupied.rbegin(), occupied.rend(), 1).base();
    int widest = 0, run = 0;
    for (auto it = first; it < last; ++it) {
      run = *it ? 0 : run + 1;
      widest = std::max(widest, run);
    }
    return widest;
  };
  const int gap_minus_y = widest_gap(true), gap_plus_y = widest_gap(false);
  RecordProperty("notch_gap_minus_y_mm", gap_minus_y);
  RecordProperty("gap_plus_y_mm", gap_plus_y);
  EXPECT_GE(gap_minus_y, 15); // the notch: about 20 mm between the condyles
  EXPECT_EQ(gap_plus_y, 0);   // the trochlea is one piece
  EXPECT_LT(mcl.V.col(0).mean(), cartilage.V.col(0).mean() - 20.0); // MCL medial, at -x
}

TEST(CondyleAxisVhf, CartilageGivesAMediolateralAxisThroughTheCondyles)
{
  const TriangleSurface cartilage =
      read_binary_stl(vhf_file("VHF_Right_Cartilage_FemurDistal_smooth.stl"));
  const TriangleSurface mcl = read_binary_stl(vhf_file("VHF_Right_Ligament_MCL_smooth.stl"));
  const CondyleAxisFit fit = fit_condyle_axis(cartilage, kVhfProximal, kVhfPosterior);
  const Eigen::Vector3d& p = fit.axis.point_mm;
  const Eigen::Vector3d& a = fit.axis.direction;
  const double to_x_deg = degrees(line_angle(a, Eigen::Vector3d::UnitX()));
  RecordProperty("point_mm", fmt::format("{:.2f} {:.2f} {:.2f}", p.x(), p.y(), p.z()));
  RecordProperty("direction", fmt::format("{:.4f} {:.4f} {:.4f}", a.x(), a.y(), a.z()));
  RecordProperty("radius_mm", fmt::format("{:.2f}", fit.radius_mm));
  RecordProperty("rms_residual_mm", fmt::format("{:.3f}", fit.rms_residual_mm));
  RecordProperty("points_used", fit.points_used);
  RecordProperty("points_considered", fit.points_considered);
  RecordProperty("iterations", fit.iterations);
  RecordProperty("angle_to_x_deg", fmt::format("{:.2f}", to_x_deg));

  EXPECT_LT(to_x_deg, 15.0);
  EXPECT_GT(fit.radius_mm, 15.0);
  EXPECT_LT(fit.radius_mm, 30.0);
  EXPECT_LT(fit.rms_residual_mm, 2.0);
  // Lateral for a right knee: away from the MCL.
  const Eigen::Vector3d mcl_centre = mcl.V.colwise().mean().transpose();
  EXPECT_GT(a.dot(p - mcl_centre), 0.0);
  EXPECT_GT(a.x(), 0.0);
  const Eigen::Vector3d low = cartilage.V.colwise().minCoeff().transpose();
  const Eigen::Vector3d high = cartilage.V.colwise().maxCoeff().transpose();
  EXPECT_TRUE((p.array() > low.array()).all() && (p.array() < high.array()).all())
      << "axis point " << p.transpose() << " outside the cartilage's box";

  // Both condyles carry the fit: used vertices on either side of the notch.
  int medial = 0, lateral = 0;
  for (const int v : fit.used_vertices)
    (cartilage.V(v, 0) < p.x() ? medial : lateral) += 1;
  RecordProperty("used_medial_lateral", fmt::format("{} {}", medial, lateral));
  EXPECT_GT(medial, fit.points_used / 5);
  EXPECT_GT(lateral, fit.points_used / 5);

  // A posterior hint 20 degrees off, about the proximal direction, changes little.
  for (const double deg : {-20.0, 20.0}) {
    const CondyleAxisFit off =
        fit_condyle_axis(cartilage, kVhfProximal, turned(kVhfPosterior, kVhfProximal, deg));
    EXPECT_LT(degrees(angle(off.axis.direction, a)), 2.0) << "hint turned " << deg << " degrees";
  }
}
