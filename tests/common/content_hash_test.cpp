#include "common/content_hash.hpp"

#include <gtest/gtest.h>

TEST(ContentHash, SameInputSameKeyDifferentInputDifferentKey)
{
  using ligsim::ContentHash;
  EXPECT_EQ(ContentHash().add("abc").hex(), ContentHash().add("abc").hex());
  EXPECT_NE(ContentHash().add("abc").hex(), ContentHash().add("abd").hex());
  EXPECT_NE(ContentHash().add("ab").add("c").hex(), ContentHash().add("a").add("bc").hex());
  EXPECT_EQ(ContentHash().add("x").hex().size(), 16u);
}
