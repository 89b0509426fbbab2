#include "common/error.hpp"
#include "sim/scene/toml_reader.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

using namespace ligsim::sim;

namespace {

std::string error_of(const std::string& text, void (*read)(TomlTable&))
{
  const toml::table root = parse_toml(text, "t.toml");
  TomlTable table(root, "t.toml");
  try {
    read(table);
  } catch (const ligsim::InputError& e) {
    return e.what();
  }
  return "no error";
}

} // namespace

TEST(TomlTable, IntegersBeyondTwoToThe53AreTheirNearestDouble)
{
  // Fuzz finding (tests/fuzz/findings/flexion_angle_beyond_2p53.toml): toml++ gives no double
  // for such an integer, and numbers() threw std::bad_optional_access.
  const toml::table root =
      parse_toml("a = [0, 500000000000000000, 9007199254740993]\nb = -9007199254740993\n"
                 "c = [1, 2, 36028797018963971]\n",
                 "t.toml");
  TomlTable table(root, "t.toml");
  const std::vector<double> a = table.numbers("a");
  ASSERT_EQ(a.size(), 3u);
  EXPECT_EQ(a[1], 5e17);
  EXPECT_EQ(a[2], 9007199254740992.0); // 2^53 + 1 rounds to even
  EXPECT_EQ(table.required_number("b"), -9007199254740992.0);
  EXPECT_EQ(table.required_vector3("c").z(), 36028797018963968.0); // 2^55 + 3 rounds to 2^55
}

TEST(TomlTable, NumbersMustBeFiniteAndIntegersFitAnInt)
{
  EXPECT_EQ(error_of("a = [1, nan]\n", [](TomlTable& t) { t.numbers("a"); }),
            "t.toml: a: expected an array of finite numbers");
  EXPECT_EQ(error_of("n = 4294967297\n", [](TomlTable& t) { t.integer("n", 0); }),
            "t.toml: n: expected an integer (at most 2147483647 in size)");
  EXPECT_EQ(error_of("n = [1, -3000000000]\n", [](TomlTable& t) { t.integers("n"); }),
            "t.toml: n: expected an array of integers (each at most 2147483647 in size)");
  EXPECT_EQ(
      error_of("n = 2147483647\n", [](TomlTable& t) { EXPECT_EQ(t.integer("n", 0), 2147483647); }),
      "no error");
}
