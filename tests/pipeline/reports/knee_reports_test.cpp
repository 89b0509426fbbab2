#include "pipeline/reports/knee_reports.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using namespace ligsim;

TEST(KneeReports, AThinLigamentsCrossSectionCarriesItsFindingAndThePublishedFigure)
{
  sim::LigamentThickness thread;
  thread.volume_mm3 = 48.0;
  thread.centerline_mm = 20.0;
  thread.mean_cross_section_mm2 = 2.4;
  const nlohmann::json acl = reports::thickness_json(thread, "ACL");
  EXPECT_EQ(acl.at("finding").get<std::string>(), *sim::thin_ligament_finding("ACL", thread));
  EXPECT_DOUBLE_EQ(acl.at("published_cross_section_mm2").at("mm2").get<double>(), 38.7);
  EXPECT_DOUBLE_EQ(acl.at("mean_cross_section_mm2").get<double>(), 2.4);
  const nlohmann::json mcl = reports::thickness_json(thread, "MCL");
  EXPECT_FALSE(mcl.contains("finding")) << "no published figure, no finding";
}

TEST(KneeReports, EachPairIsWrittenWithItsAngle)
{
  sim::LigamentPair pair;
  pair.first = "ACL";
  pair.second = "PCL";
  pair.closest_mm = 3.3;
  pair.nodes_inside = 2;
  pair.deepest_mm = 0.4;
  const nlohmann::json json =
      reports::to_json(std::vector<sim::PairAtAngle>{{30.0, pair}, {60.0, pair}});
  ASSERT_EQ(json.size(), 2u);
  EXPECT_DOUBLE_EQ(json[1].at("angle_deg").get<double>(), 60.0);
  EXPECT_EQ(json[0].at("first").get<std::string>(), "ACL");
  EXPECT_EQ(json[0].at("second").get<std::string>(), "PCL");
  EXPECT_DOUBLE_EQ(json[0].at("closest_mm").get<double>(), 3.3);
  EXPECT_EQ(json[0].at("nodes_inside").get<int>(), 2);
  EXPECT_DOUBLE_EQ(json[0].at("deepest_mm").get<double>(), 0.4);
}

TEST(KneeReports, AnOverlapNotPushedSaysOnlyTheGapsBefore)
{
  sim::OverlapReport report;
  report.before.push_back({"femur", 0.3, 0, 12, {}});
  nlohmann::json json = reports::to_json(report);
  EXPECT_FALSE(json.at("pushed").get<bool>());
  EXPECT_DOUBLE_EQ(json.at("before").at("femur").at("min_gap_mm").get<double>(), 0.3);
  EXPECT_EQ(json.at("before").at("femur").at("nodes_within_d_hat").get<int>(), 12);
  EXPECT_FALSE(json.contains("after"));

  report.pushed = true;
  report.after = report.before;
  report.newton_iterations = 7;
  json = reports::to_json(report);
  EXPECT_EQ(json.at("newton_iterations").get<int>(), 7);
  EXPECT_FALSE(json.at("reshaped").get<bool>());
  EXPECT_TRUE(json.contains("after"));
}

} // namespace
