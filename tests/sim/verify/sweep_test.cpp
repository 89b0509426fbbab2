/// sim/verify/sweep: FEBio's own solution is a point of the error-against-time plot, at the wall
/// time cases.json records and placed by the same measure as ours (error against the finest
/// mesh), so it lands on our 16^3 point's error.

#include "sim/verify/febio_reference.hpp"
#include "sim/verify/sweep.hpp"

#include <gtest/gtest.h>

#include <algorithm>

using namespace ligsim::sim;

TEST(CubeSweep, FebioPointSitsAtItsRecordedTimeAndOurErrorAt16Cells)
{
  const FebioReference reference = read_febio_reference(LIGSIM_SOURCE_DIR "/data/febio-cube");
  const auto c = std::find_if(reference.cases.begin(), reference.cases.end(),
                              [](const FebioCase& k) { return k.name == "par_t002_pen"; });
  ASSERT_NE(c, reference.cases.end());
  SweepSettings settings;
  settings.mesh_cells = {16};
  settings.finest_cells = 6; // coarse, quick: only the agreement of the two 16^3 points matters
  settings.tolerances = {};
  const std::vector<SweepRow> rows = run_sweep(reference, *c, settings);

  const SweepRow* febio = nullptr;
  const SweepRow* ours = nullptr;
  for (const SweepRow& r : rows) {
    if (r.family == "febio")
      febio = &r;
    if (r.family == "mesh" && r.linear_solver == "direct")
      ours = &r;
  }
  ASSERT_NE(febio, nullptr);
  ASSERT_NE(ours, nullptr);
  EXPECT_DOUBLE_EQ(febio->wall_s, c->febio.wall_s.value());
  EXPECT_EQ(febio->elements, 16 * 16 * 16 * 5);
  EXPECT_EQ(febio->elements, ours->elements);
  // Our 16^3 solution equals FEBio's to 1e-7 % of the edge, so both are as far from the finest.
  EXPECT_GT(ours->avg_error_finest_pct, 1e-3);
  EXPECT_NEAR(febio->avg_error_finest_pct, ours->avg_error_finest_pct, 1e-5);
  EXPECT_NEAR(febio->avg_top_uz_mm, ours->avg_top_uz_mm, 1e-8);

  const ligsim::PlotSpec plot = sweep_plot(rows, c->name);
  ASSERT_FALSE(plot.series.empty());
  EXPECT_EQ(plot.series.back().name, "FEBio 4.11 (recorded time)");
  EXPECT_DOUBLE_EQ(plot.series.back().x.at(0), febio->wall_s);
}
