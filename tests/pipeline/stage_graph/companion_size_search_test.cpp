/// The companion's size search on meshers stood in for by functions: how the elements grow with
/// the factor on the sizes, and where the mesher makes nothing.

#include "pipeline/stage_graph/companion_size_search.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

using namespace ligsim::pipeline;

TEST(CompanionSizeSearch, ReachesTheRatioOnABandWhoseElementsGrowSlowly)
{
  // Elements growing as the factor to the 0.25 (a band keeping its tets across its thickness):
  // 1.5 needs a factor of 5.06.
  std::vector<double> tried;
  const SizeSearch search = search_size_factor(1.5, 1.5, [&](double scale) {
    tried.push_back(scale);
    return SizeTry{std::pow(scale, 0.25)};
  });
  EXPECT_NEAR(search.size_ratio, 1.5, 1.5 * 0.05);
  EXPECT_NEAR(search.scale, std::pow(1.5, 4.0), 0.5);
  EXPECT_EQ(search.meshings, 2);
  EXPECT_EQ(tried.size(), 2u);
}

TEST(CompanionSizeSearch, AFactorTooCoarseForTheSurfaceSendsItBackAndTheSearchStillEnds)
{
  // The elements grow as the factor to the 0.2 (1.5 needs 7.6), but the mesher makes nothing
  // beyond a factor of 6: the HRA male MCL at a facet distance of 0.08 mm went to the largest
  // factor, 8, and was left without a companion.
  std::vector<double> tried;
  const SizeSearch search = search_size_factor(1.5, 1.5, [&](double scale) {
    tried.push_back(scale);
    if (scale > 6.0)
      throw std::runtime_error("Mesh_3 produced no tetrahedra");
    return SizeTry{std::pow(scale, 0.2)};
  });
  ASSERT_GE(tried.size(), 3u);
  EXPECT_GT(tried[1], 6.0); // the line through the first mesh overshoots into the failure
  EXPECT_LE(search.scale, 6.0);
  EXPECT_GT(search.size_ratio, 1.3); // the least ratio the estimate takes (Celik et al. 2008)
  EXPECT_LE(search.meshings, 6);
  for (std::size_t i = 2; i < tried.size(); ++i)
    EXPECT_LT(tried[i], tried[1]) << "no factor past the one that failed";
}

TEST(CompanionSizeSearch, AMesherThatFailsEveryTimeIsAnError)
{
  int calls = 0;
  EXPECT_THROW(search_size_factor(1.5, 1.5,
                                  [&](double) -> SizeTry {
                                    ++calls;
                                    throw std::runtime_error("no mesh");
                                  }),
               std::runtime_error);
  EXPECT_EQ(calls, 6);
}

TEST(CompanionSizeSearch, AnUnchangedRebuildKeepsThePreviousCompanionThoughItMissedTheRatio)
{
  // The previous build ended at a factor of 2 with elements 1.1 times as large (a band too
  // coarse to reach 1.5); its companion is current, and searching on from it would end elsewhere
  // than the build that made it.
  int calls = 0;
  const SizeSearch search = search_size_factor(2.0, 1.5, [&](double scale) {
    ++calls;
    return SizeTry{1.1, scale == 2.0};
  });
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(search.scale, 2.0);
  EXPECT_EQ(search.size_ratio, 1.1);
}
