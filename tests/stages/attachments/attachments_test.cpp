#include "common/error.hpp"
#include "stages/attachments/attachments.hpp"
#include "stages/synthetic/shapes.hpp"

#include <gtest/gtest.h>

#include <array>
#include <set>
#include <vector>

using namespace ligsim;

namespace {
const synthetic::Shape& band()
{
  static const synthetic::Shape shape = synthetic::ligament_band();
  return shape;
}
} // namespace

TEST(Attachments, ProximityToBothBonesOnTheBand)
{
  attachments::Inputs inputs{&band().surface, &*band().femur, &*band().tibia, {}};
  const auto found = attachments::find(inputs, {}, {});
  EXPECT_NE(found.femur.rule.find("proximity"), std::string::npos);
  EXPECT_NE(found.tibia.rule.find("proximity"), std::string::npos);
  // The femur proxy caps the top end; the tibia proxy hugs the inner side of the distal
  // quarter (20.4 mm of arc): its area is that side, up to the proximity distance beyond.
  EXPECT_GT(found.femur.mean.z(), 75.0);
  EXPECT_LT(found.tibia.mean.z(), 12.0);
  EXPECT_GT(found.tibia.vertices.size(), 100u);
  for (int v : found.tibia.vertices) {
    EXPECT_LE(band().surface.V(v, 2), 21.5);
    EXPECT_LT(band().surface.V(v, 0), band().axis.point(band().surface.V(v, 2) / 82.0).x());
  }
}

TEST(Attachments, FemurDefaultsToTheEndFarthestFromTheTibia)
{
  attachments::Inputs inputs{&band().surface, nullptr, &*band().tibia, {}};
  const auto found = attachments::find(inputs, {}, {});
  EXPECT_NE(found.femur.rule.find("end"), std::string::npos);
  EXPECT_GT(found.femur.mean.z(), 75.0);
}

TEST(Attachments, WithNothingGivenTheEndsAlongTheMainAxisAreUsed)
{
  attachments::Inputs inputs{&band().surface, nullptr, nullptr, {}};
  const auto found = attachments::find(inputs, {}, {});
  EXPECT_GT(found.femur.mean.z(), 75.0);
  EXPECT_LT(found.tibia.mean.z(), 5.0);
}

TEST(Attachments, IndicesAndArrays)
{
  attachments::Inputs inputs{&band().surface, nullptr, nullptr, {}};
  inputs.arrays["insertion"] = Eigen::VectorXd::Zero(band().surface.V.rows());
  inputs.arrays["insertion"][5] = 1.0;
  attachments::Rule femur, tibia;
  femur.indices = {1, 2, 3};
  tibia.array = "insertion";
  const auto found = attachments::find(inputs, femur, tibia);
  EXPECT_EQ(found.femur.vertices, (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(found.tibia.vertices, (std::vector<int>{5}));
}

TEST(Attachments, BadRulesAreClearErrors)
{
  attachments::Inputs inputs{&band().surface, nullptr, &*band().tibia, {}};
  attachments::Rule femur, tibia;
  femur.indices = {1, 2, 3};
  tibia.indices = {3, 4};
  EXPECT_THROW(attachments::find(inputs, femur, tibia), InputError); // overlap

  attachments::Rule far;
  far.rule = "proximity";
  far.distance_mm = 1e-6;
  attachments::Rule none;
  none.rule = "proximity";
  EXPECT_THROW(attachments::find(inputs, none, {}), InputError); // no femur surface
  EXPECT_THROW(attachments::find(inputs, {}, far), InputError);  // empty area

  attachments::Rule bad;
  bad.indices = {-1};
  EXPECT_THROW(attachments::find(inputs, bad, {}), InputError);
  attachments::Rule unknown;
  unknown.rule = "nearest";
  EXPECT_THROW(attachments::find(inputs, unknown, {}), InputError);
}

namespace {
const synthetic::Shape& tube()
{
  static const synthetic::Shape shape = synthetic::cylinder(3.0, 30.0);
  return shape;
}
} // namespace

TEST(Footprints, AnatomicalEndsFollowTheProximalDirection)
{
  attachments::Inputs inputs{&tube().surface, nullptr, nullptr, {}};
  inputs.proximal = Eigen::Vector3d(0.0, 0.0, -1.0); // this leg is upside down in its frame
  attachments::Rule femur, tibia;
  femur.rule = tibia.rule = "end";
  const auto found = attachments::find(inputs, femur, tibia); // "auto" ends: proximal, distal
  EXPECT_LT(found.femur.mean.z(), 3.0);
  EXPECT_GT(found.tibia.mean.z(), 27.0);
  femur.end = "distal";
  tibia.end = "proximal";
  const auto swapped = attachments::find(inputs, femur, tibia);
  EXPECT_GT(swapped.femur.mean.z(), 27.0);
  inputs.proximal.reset();
  EXPECT_THROW(attachments::find(inputs, femur, tibia), InputError); // proximal unknown
}

TEST(Footprints, LandmarkWithAnatomicalOffsetsAndItsArea)
{
  attachments::Inputs inputs{&tube().surface, nullptr, nullptr, {}};
  inputs.landmarks["medial_epicondyle"] = Eigen::Vector3d(3.0, 0.0, 20.0); // on the side
  inputs.proximal = Eigen::Vector3d::UnitZ();
  inputs.posterior = Eigen::Vector3d::UnitY();
  attachments::Rule femur, tibia;
  femur.rule = "landmark";
  femur.landmark = "medial_epicondyle";
  femur.proximal_mm = 5.0;
  femur.posterior_mm = 0.0;
  femur.radius_mm = 2.0;
  tibia.rule = "end";
  const auto found = attachments::find(inputs, femur, tibia);
  for (int v : found.femur.vertices)
    EXPECT_LE((tube().surface.V.row(v).transpose() - Eigen::Vector3d(3.0, 0.0, 25.0)).norm(),
              2.0 + 1e-12);
  // A disc of radius 2 mm on a cylinder of radius 3 mm: about pi 2^2 = 12.6 mm^2 of surface,
  // less the triangles cut by its rim (each counted by the share of its corners inside).
  EXPECT_GT(found.femur.area_mm2, 0.6 * M_PI * 4.0);
  EXPECT_LT(found.femur.area_mm2, 1.2 * M_PI * 4.0);
  EXPECT_LE(found.femur.extent_mm, 4.0 + 1e-9);
  EXPECT_GT(found.femur.extent_mm, 3.0);

  femur.landmark = "lateral_epicondyle";
  EXPECT_THROW(attachments::find(inputs, femur, tibia), InputError); // unknown landmark
  femur.landmark.clear();
  EXPECT_THROW(attachments::find(inputs, femur, tibia), InputError); // neither name nor point
  femur.point_mm = Eigen::Vector3d(3.0, 0.0, 20.0);
  inputs.posterior.reset();
  femur.posterior_mm = 1.0;
  EXPECT_THROW(attachments::find(inputs, femur, tibia), InputError); // offset needs posterior
}

TEST(Footprints, PatchAndTheSideNextToTheBone)
{
  // The patch: a small square sheet touching the tube's +x side near its top.
  TriangleSurface patch;
  patch.V.resize(4, 3);
  patch.V << 3.2, -2.0, 24.0, 3.2, 2.0, 24.0, 3.2, 2.0, 28.0, 3.2, -2.0, 28.0;
  patch.F.resize(2, 3);
  patch.F << 0, 1, 2, 0, 2, 3;
  attachments::Inputs inputs{&tube().surface, nullptr, nullptr, {}};
  inputs.femur_patch = &patch;
  attachments::Rule femur, tibia;
  femur.rule = "patch";
  femur.distance_mm = 1.0;
  tibia.rule = "end";
  const auto found = attachments::find(inputs, femur, tibia);
  EXPECT_GT(found.femur.vertices.size(), 3u);
  for (int v : found.femur.vertices)
    EXPECT_GT(tube().surface.V(v, 0), 2.0);
  inputs.femur_patch = nullptr;
  EXPECT_THROW(attachments::find(inputs, femur, tibia), InputError);

  // Near the bone: the distal end keeps only the side the tibia proxy lies against (x < 0).
  TriangleSurface bone;
  bone.V.resize(4, 3);
  bone.V << -3.3, -5.0, -1.0, -3.3, 5.0, -1.0, -3.3, 5.0, 8.0, -3.3, -5.0, 8.0;
  bone.F.resize(2, 3);
  bone.F << 0, 1, 2, 0, 2, 3;
  attachments::Inputs near{&tube().surface, nullptr, &bone, {}};
  attachments::Rule top, bottom;
  top.rule = bottom.rule = "end";
  top.end = "max";
  bottom.end = "min";
  bottom.end_length_mm = 6.0;
  const auto whole = attachments::find(near, top, bottom);
  bottom.bone_distance_mm = 1.0;
  const auto side = attachments::find(near, top, bottom);
  EXPECT_LT(side.tibia.vertices.size(), whole.tibia.vertices.size() / 2);
  EXPECT_LT(side.tibia.area_mm2, 0.5 * whole.tibia.area_mm2);
  for (int v : side.tibia.vertices)
    EXPECT_LT(tube().surface.V(v, 0), -2.0);
}

namespace {
/// The closed box [-5, 5] x [-5, 5] x [-1, top], outward triangles; without its top face when
/// `open`.
TriangleSurface box_bone(double top, bool open)
{
  TriangleSurface box;
  box.V.resize(8, 3);
  for (int c = 0; c < 8; ++c)
    box.V.row(c) << (c & 1 ? 5.0 : -5.0), (c & 2 ? 5.0 : -5.0), (c & 4 ? top : -1.0);
  std::vector<std::array<int, 3>> faces = {{0, 2, 1}, {1, 2, 3}, {0, 1, 5}, {0, 5, 4}, {1, 3, 7},
                                           {1, 7, 5}, {3, 2, 6}, {3, 6, 7}, {2, 0, 4}, {2, 4, 6}};
  if (!open)
    faces.insert(faces.end(), {{4, 5, 7}, {4, 7, 6}});
  box.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    box.F.row(static_cast<Eigen::Index>(f)) << faces[f][0], faces[f][1], faces[f][2];
  return box;
}
} // namespace

TEST(Footprints, ProximityTakesTheLigamentInsideAClosedBone)
{
  // The tube (radius 3 mm, z 0 to 30) enters a closed box bone up to z = 8: its wall lies 2 mm
  // from the box's sides, deeper than the 1 mm proximity, yet it is attached there.
  const TriangleSurface closed = box_bone(8.0, false);
  attachments::Inputs inputs{&tube().surface, nullptr, &closed, {}};
  attachments::Rule femur, tibia;
  femur.rule = "end";
  femur.end = "max";
  tibia.rule = "proximity";
  tibia.distance_mm = 1.0;
  const auto found = attachments::find(inputs, femur, tibia);
  const std::set<int> taken(found.tibia.vertices.begin(), found.tibia.vertices.end());
  int inside = 0;
  for (Eigen::Index v = 0; v < tube().surface.V.rows(); ++v) {
    const double z = tube().surface.V(v, 2);
    if (z < 7.9) {
      EXPECT_TRUE(taken.count(static_cast<int>(v))) << "vertex " << v << " at z " << z;
      ++inside;
    }
    if (z > 9.1)
      EXPECT_FALSE(taken.count(static_cast<int>(v))) << "vertex " << v << " at z " << z;
  }
  EXPECT_GT(inside, 20);
  ASSERT_EQ(found.tibia.corrections.size(), 1u);
  EXPECT_NE(found.tibia.corrections[0].find("inside the bone"), std::string::npos);

  // An open bone has no inside: only the vertices within 1 mm of it.
  const TriangleSurface open = box_bone(8.0, true);
  inputs.tibia = &open;
  const auto near_only = attachments::find(inputs, femur, tibia);
  for (int v : near_only.tibia.vertices) {
    const Eigen::Vector3d p = tube().surface.V.row(v).transpose();
    EXPECT_TRUE(p.z() < 0.01 || p.z() > 6.99) << "vertex " << v << " at z " << p.z();
  }
  EXPECT_TRUE(near_only.tibia.corrections.empty());
}

TEST(Footprints, ALandmarkThatMissesTheLigamentSnapsToItsEnd)
{
  // The tube (radius 3 mm, z 0 to 30) and a landmark 9 mm off its side near its top.
  attachments::Inputs inputs{&tube().surface, nullptr, nullptr, {}};
  inputs.landmarks["medial_epicondyle"] = Eigen::Vector3d(12.0, 0.0, 26.0);
  inputs.proximal = Eigen::Vector3d::UnitZ();
  attachments::Rule femur, tibia;
  femur.rule = "landmark";
  femur.landmark = "medial_epicondyle";
  femur.radius_mm = 2.0;
  tibia.rule = "end";
  EXPECT_THROW(attachments::find(inputs, femur, tibia), InputError); // the disc holds nothing
  femur.snap = true;
  const auto snapped = attachments::find(inputs, femur, tibia);
  ASSERT_EQ(snapped.femur.corrections.size(), 1u);
  EXPECT_NE(snapped.femur.corrections[0].find("missed the ligament by 9.0 mm"), std::string::npos)
      << snapped.femur.corrections[0];
  // The disc sits on the tube's +x side at the landmark's height, within the proximal end.
  EXPECT_GT(snapped.femur.mean.x(), 1.5);
  EXPECT_NEAR(snapped.femur.mean.z(), 26.0, 1.0);
  for (int v : snapped.femur.vertices)
    EXPECT_GT(tube().surface.V(v, 2), 30.0 - 3.0 * femur.radius_mm - femur.radius_mm - 1e-9);

  // Held to its published place: 9 mm away is refused when 5 mm is the most it may be.
  femur.max_distance_mm = 5.0;
  try {
    attachments::find(inputs, femur, tibia);
    FAIL() << "a footprint 9 mm from its landmark was taken";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("farther than the 5.0 mm"), std::string::npos) << e.what();
  }

  // No such landmark in the anatomy: the ligament's end toward the femur, said so.
  inputs.landmarks.clear();
  femur.max_distance_mm = 0.0;
  const auto end = attachments::find(inputs, femur, tibia);
  EXPECT_GT(end.femur.mean.z(), 27.0);
  ASSERT_EQ(end.femur.corrections.size(), 1u);
  EXPECT_NE(end.femur.corrections[0].find("no medial_epicondyle"), std::string::npos);
}

TEST(Footprints, AFootprintLargerThanItsPublishedBoundShrinksOrIsRefused)
{
  attachments::Inputs inputs{&tube().surface, nullptr, nullptr, {}};
  inputs.landmarks["lateral_epicondyle"] = Eigen::Vector3d(3.0, 0.0, 20.0);
  attachments::Rule femur, tibia;
  femur.rule = "landmark";
  femur.landmark = "lateral_epicondyle";
  femur.radius_mm = 4.0;
  tibia.rule = "end";
  const double whole = attachments::find(inputs, femur, tibia).femur.area_mm2;
  femur.max_area_mm2 = 0.5 * whole;
  const auto held = attachments::find(inputs, femur, tibia);
  EXPECT_LE(held.femur.area_mm2, 0.5 * whole);
  EXPECT_GT(held.femur.area_mm2, 0.25 * whole); // shrunk by tenths of the radius, not more
  ASSERT_FALSE(held.femur.corrections.empty());
  EXPECT_NE(held.femur.corrections.back().find("shrunk from 4"), std::string::npos);
  // A rule without a disc cannot shrink: refused, saying what to give.
  tibia.max_area_mm2 = 1.0;
  try {
    attachments::find(inputs, femur, tibia);
    FAIL() << "an end larger than its bound was taken";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("more than the 1 mm^2"), std::string::npos) << e.what();
  }
}
