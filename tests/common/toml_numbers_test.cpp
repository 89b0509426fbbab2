#include "common/toml_numbers.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace ligsim {
namespace {

TEST(TomlNumbers, IntegersAndFloatsAreNumbersAndNothingElseIs)
{
  const toml::table table =
      toml::parse("i = -7\nf = 2.5\ninf = inf\ns = \"3\"\nb = true\na = [1]\n");
  EXPECT_EQ(toml_number(*table.get("i")), -7.0);
  EXPECT_EQ(toml_number(*table.get("f")), 2.5);
  ASSERT_TRUE(toml_number(*table.get("inf")));
  EXPECT_TRUE(std::isinf(*toml_number(*table.get("inf")))); // finiteness is the reader's call
  EXPECT_FALSE(toml_number(*table.get("s")));
  EXPECT_FALSE(toml_number(*table.get("b")));
  EXPECT_FALSE(toml_number(*table.get("a")));
}

// toml++'s value<double>() refuses these (not exact in a double); readers then said
// "expected a number" of a number.
TEST(TomlNumbers, IntegerBeyondTwoToThe53IsItsNearestDouble)
{
  const toml::table table = toml::parse("big = 9007199254740993\nhuge = -500000000000000000\n");
  EXPECT_EQ(toml_number(*table.get("big")), 9007199254740992.0);
  EXPECT_EQ(toml_number(*table.get("huge")), -5e17);
}

TEST(TomlNumbers, IntOnlyForIntegersInIntRange)
{
  const toml::table table = toml::parse("a = 2147483647\nb = -2147483648\nc = 2147483648\n"
                                        "d = 5000000000\ne = 3.0\nf = \"4\"\n");
  EXPECT_EQ(toml_int(*table.get("a")), 2147483647);
  EXPECT_EQ(toml_int(*table.get("b")), -2147483647 - 1);
  EXPECT_FALSE(toml_int(*table.get("c")));
  EXPECT_FALSE(toml_int(*table.get("d"))); // a cast would make it 705032704
  EXPECT_FALSE(toml_int(*table.get("e")));
  EXPECT_FALSE(toml_int(*table.get("f")));
}

} // namespace
} // namespace ligsim
