#include "sim/contact/barrier.hpp"

#include <gtest/gtest.h>

using namespace ligsim::sim;

TEST(IpcBarrier, DerivativesMatchFiniteDifferences)
{
  const double d_hat = 0.3;
  for (double d : {0.001, 0.01, 0.05, 0.1, 0.2, 0.29}) {
    const double h = 1e-6 * d;
    const BarrierValue b = ipc_barrier(d, d_hat);
    const BarrierValue plus = ipc_barrier(d + h, d_hat);
    const BarrierValue minus = ipc_barrier(d - h, d_hat);
    EXPECT_NEAR(b.first, (plus.value - minus.value) / (2 * h), 1e-6 * std::abs(b.first) + 1e-12);
    EXPECT_NEAR(b.second, (plus.first - minus.first) / (2 * h), 1e-6 * std::abs(b.second) + 1e-9);
    EXPECT_GT(b.value, 0.0);
    EXPECT_LT(b.first, 0.0);
    EXPECT_GT(b.second, 0.0);
  }
}

TEST(IpcBarrier, VanishesBeyondDhatAndIsInfiniteAtContact)
{
  EXPECT_EQ(ipc_barrier(0.3, 0.3).value, 0.0);
  EXPECT_EQ(ipc_barrier(1.0, 0.3).first, 0.0);
  EXPECT_TRUE(std::isinf(ipc_barrier(0.0, 0.3).value));
  EXPECT_TRUE(std::isinf(ipc_barrier(-0.1, 0.3).value));
  // C1 at d_hat: value and slope tend to zero.
  const BarrierValue near = ipc_barrier(0.3 - 1e-7, 0.3);
  EXPECT_LT(near.value, 1e-13);
  EXPECT_LT(std::abs(near.first), 1e-12);
}
