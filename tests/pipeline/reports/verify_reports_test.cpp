#include "pipeline/reports/verify_reports.hpp"

#include <gtest/gtest.h>

namespace ligsim::reports {
namespace {

TEST(FebioReference, VerifyJsonHasTheIssueSchema)
{
  sim::CubeCaseResult result;
  result.name = "x";
  result.converged = true;
  const nlohmann::json json = to_json(std::vector<sim::CubeCaseResult>{result});
  for (const char* key :
       {"name", "energy", "avg_error_pct", "max_error_pct", "avg_error_all_pct",
        "max_error_all_pct", "avg_fiber_strain_pct", "volume_change_pct", "wall_s", "febio_wall_s"})
    EXPECT_TRUE(json["cases"][0].contains(key)) << key;
  EXPECT_EQ(json["cases"][0]["energy"], "matched");
}

} // namespace
} // namespace ligsim::reports
