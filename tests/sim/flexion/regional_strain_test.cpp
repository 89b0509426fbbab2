/// The regional peak of a per-element value: regions against a brute-force search, a uniform
/// field kept, a single hot element diluted as the mesh refines, bad radii refused.

#include "common/error.hpp"
#include "sim/flexion/flexion_config.hpp"
#include "sim/flexion/regional_strain.hpp"

#include <gtest/gtest.h>

#include <random>

using namespace ligsim::sim;

namespace {

/// Centroids of a cubic lattice of n^3 cells of edge h, each of volume h^3.
std::pair<Eigen::MatrixX3d, Eigen::VectorXd> lattice(int n, double h)
{
  Eigen::MatrixX3d centroids(n * n * n, 3);
  int row = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        centroids.row(row++) = h * Eigen::RowVector3d(i + 0.5, j + 0.5, k + 0.5);
  return {centroids, Eigen::VectorXd::Constant(n * n * n, h * h * h)};
}

} // namespace

TEST(RegionalMean, EqualsTheBruteForceMeanOverTheSphere)
{
  // Random points on both sides of zero, so regions cross grid cells and the origin.
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-6.0, 6.0);
  std::uniform_real_distribution<double> positive(0.1, 2.0);
  const int count = 600;
  Eigen::MatrixX3d centroids(count, 3);
  Eigen::VectorXd volumes(count);
  Eigen::VectorXd values(count);
  for (int e = 0; e < count; ++e) {
    centroids.row(e) << coordinate(random), coordinate(random), coordinate(random);
    volumes[e] = positive(random);
    values[e] = coordinate(random);
  }
  const double radius = 1.7;
  const RegionalMean regions(centroids, volumes, radius);
  double largest = -INFINITY;
  for (int e = 0; e < count; ++e) {
    double sum = 0.0;
    double volume = 0.0;
    for (int o = 0; o < count; ++o)
      if ((centroids.row(o) - centroids.row(e)).norm() <= radius) {
        sum += volumes[o] * values[o];
        volume += volumes[o];
      }
    EXPECT_NEAR(regions.mean(values, e), sum / volume, 1e-12) << "element " << e;
    largest = std::max(largest, sum / volume);
  }
  EXPECT_NEAR(regions.max_mean(values), largest, 1e-12);
}

TEST(RegionalMean, RegionsTooLargeToListGiveTheSameAsTheListedOnes)
{
  // 7,000 elements in a 3 mm cube with 2 mm regions: each region holds thousands, too many to
  // list (4 million entries at most), so every call searches the grid; a few hundred of them
  // with 0.6 mm regions are listed. Both give mean()'s maximum exactly (the same sums).
  std::mt19937 random(11);
  std::uniform_real_distribution<double> coordinate(0.0, 3.0);
  std::uniform_real_distribution<double> positive(0.1, 2.0);
  const int count = 7000;
  Eigen::MatrixX3d centroids(count, 3);
  Eigen::VectorXd volumes(count), values(count);
  for (int e = 0; e < count; ++e) {
    centroids.row(e) << coordinate(random), coordinate(random), coordinate(random);
    volumes[e] = positive(random);
    values[e] = coordinate(random);
  }
  const RegionalMean dense(centroids, volumes, 2.0);
  double largest = -INFINITY;
  for (int e = 0; e < count; ++e)
    largest = std::max(largest, dense.mean(values, e));
  EXPECT_EQ(dense.max_mean(values), largest);
  EXPECT_EQ(dense.max_mean(values), largest); // the second call searches again, alike

  // A small set listed: the listed figure equals mean()'s maximum exactly.
  const RegionalMean sparse(centroids.topRows(500), volumes.head(500), 0.6);
  double listed_largest = -INFINITY;
  for (int e = 0; e < 500; ++e)
    listed_largest = std::max(listed_largest, sparse.mean(values.head(500), e));
  EXPECT_EQ(sparse.max_mean(values.head(500)), listed_largest);
  EXPECT_EQ(sparse.max_mean(values.head(500)), listed_largest);
}

TEST(RegionalMean, KeepsAUniformField)
{
  const auto [centroids, volumes] = lattice(6, 0.5);
  const RegionalMean regions(centroids, volumes, 2.0);
  EXPECT_NEAR(regions.max_mean(Eigen::VectorXd::Constant(volumes.size(), 0.08)), 0.08, 1e-15);
}

TEST(RegionalMean, DilutesOneHotElementMoreOnAFinerMesh)
{
  // One element strained 100 % among unstrained ones: its element maximum stays 1 whatever the
  // mesh, its regional peak falls with the element's share of the 2 mm sphere.
  double previous = INFINITY;
  for (int n : {8, 16, 32}) {
    const double h = 8.0 / n;
    const auto [centroids, volumes] = lattice(n, h);
    Eigen::VectorXd strain = Eigen::VectorXd::Zero(volumes.size());
    strain[(n / 2) * n * n + (n / 2) * n + n / 2] = 1.0;
    const RegionalMean regions(centroids, volumes, 2.0);
    const double peak = regions.max_mean(strain);
    EXPECT_GT(peak, 0.0);
    EXPECT_LT(peak, 0.5 * previous) << n << " cells a side";
    previous = peak;
  }
}

TEST(RegionalMean, RefusesABadRadiusOrSizes)
{
  const auto [centroids, volumes] = lattice(2, 1.0);
  EXPECT_THROW(RegionalMean(centroids, volumes, 0.0), ligsim::InputError);
  EXPECT_THROW(RegionalMean(centroids, volumes, NAN), ligsim::InputError);
  EXPECT_THROW(RegionalMean(centroids, Eigen::VectorXd::Ones(3), 1.0), ligsim::InputError);
  const RegionalMean regions(centroids, volumes, 1.0);
  EXPECT_THROW(regions.max_mean(Eigen::VectorXd::Ones(3)), ligsim::InputError);
}

TEST(RegionalMean, TheFlexionConfigSetsTheRadiusAndRefusesZero)
{
  FlexionSettings settings;
  parse_flexion_config("[ligament]\nstrain_region_radius_mm = 3.5\n", "/", "f.toml", settings);
  EXPECT_EQ(settings.ligament.strain_region_radius_mm, 3.5);
  EXPECT_THROW(
      parse_flexion_config("[ligament]\nstrain_region_radius_mm = 0\n", "/", "f.toml", settings),
      ligsim::InputError);
}
