// The independent penetration check on a bone of two separate closed shells, the second with
// every triangle flipped (as a mis-oriented export or a stray piece can come). The sign of the
// nearest triangle's normal (vtkImplicitPolyDataDistance, the check before) read 0 at (25, 5, 4)
// and (29, 5, 5) inside the flipped cube, 1 mm at (25, 5, 11) above it and 5 mm at (15, 5, 5)
// between the cubes: four assertions below fail with it.

#include "sim/contact/bone_penetration.hpp"

#include <gtest/gtest.h>

using namespace ligsim;
using namespace ligsim::sim;

namespace {

/// Two 10 mm cubes, [0, 10]^3 (outward) and [20, 30] x [0, 10] x [0, 10] (inward).
TriangleSurface two_cubes()
{
  TriangleSurface s;
  s.V.resize(16, 3);
  s.F.resize(24, 3);
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}}; // outward, corner bits zyx
  for (int cube = 0; cube < 2; ++cube) {
    for (int corner = 0; corner < 8; ++corner)
      s.V.row(8 * cube + corner) << 20.0 * cube + 10.0 * (corner & 1), 10.0 * ((corner >> 1) & 1),
          10.0 * ((corner >> 2) & 1);
    for (int q = 0; q < 6; ++q) {
      const int* c = quads[q];
      const int o = 8 * cube;
      s.F.row(12 * cube + 2 * q) << o + c[0], o + c[1], o + c[2];
      s.F.row(12 * cube + 2 * q + 1) << o + c[0], o + c[2], o + c[3];
      if (cube == 1) {
        s.F.row(12 * cube + 2 * q).reverseInPlace();
        s.F.row(12 * cube + 2 * q + 1).reverseInPlace();
      }
    }
  }
  return s;
}

} // namespace

TEST(BonePenetration, DepthInsideEitherShellAndZeroOutsideBoth)
{
  const TriangleSurface bone = two_cubes();
  const BonePenetration check(bone);
  EXPECT_NEAR(check.depth_mm({5, 5, 5}), 5.0, 1e-9);
  EXPECT_NEAR(check.depth_mm({2, 6, 7}), 2.0, 1e-9);
  EXPECT_NEAR(check.depth_mm({25, 5, 4}), 4.0, 1e-9); // inside the flipped cube
  EXPECT_NEAR(check.depth_mm({29, 5, 5}), 1.0, 1e-9);
  EXPECT_EQ(check.depth_mm({15, 5, 5}), 0.0);  // between them
  EXPECT_EQ(check.depth_mm({25, 5, 11}), 0.0); // 1 mm above the flipped cube
  EXPECT_EQ(check.depth_mm({5, 5, 10.5}), 0.0);
  EXPECT_EQ(check.depth_mm({300, -200, 40}), 0.0); // far outside the box
}

TEST(BonePenetration, SmallHoleDoesNotTurnTheInsideOut)
{
  TriangleSurface bone = two_cubes();
  bone.F.row(0) = bone.F.row(bone.F.rows() - 1); // half of the first cube's bottom gone
  bone.F.conservativeResize(bone.F.rows() - 1, 3);
  const BonePenetration check(bone);
  EXPECT_NEAR(check.depth_mm({5, 5, 5}), 5.0, 1e-9);
  EXPECT_NEAR(check.depth_mm({4, 4, 1}), 1.0, 1e-9); // 1 mm above the hole
  EXPECT_EQ(check.depth_mm({5, 5, -1}), 0.0);
}
