#include "common/error.hpp"
#include "stages/attachments/attachments.hpp"
#include "stages/synthetic/shapes.hpp"

#include <gtest/gtest.h>

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
