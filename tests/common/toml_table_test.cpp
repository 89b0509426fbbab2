#include "common/error.hpp"
#include "common/toml_table.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

using namespace ligsim;

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
            "t.toml:1: a: expected an array of finite numbers");
  EXPECT_EQ(error_of("n = 4294967297\n", [](TomlTable& t) { t.integer("n", 0); }),
            "t.toml:1: n: expected an integer (at most 2147483647 in size)");
  EXPECT_EQ(error_of("n = [1, -3000000000]\n", [](TomlTable& t) { t.integers("n"); }),
            "t.toml:1: n: expected an array of integers (each at most 2147483647 in size)");
  EXPECT_EQ(
      error_of("n = 2147483647\n", [](TomlTable& t) { EXPECT_EQ(t.integer("n", 0), 2147483647); }),
      "no error");
}

TEST(TomlTable, MessagesNameTheFileLineTableAndKey)
{
  const toml::table root = parse_toml("top = 1\n[contact]\nstiffness = \"x\"\n[[contact.bone]]\n"
                                      "name = \"femur\"\nfolows = \"x\"\n",
                                      "knee.toml");
  TomlTable top(root, "knee.toml");
  top.integer("top", 0);
  TomlTable contact = top.required_table("contact");
  EXPECT_EQ(contact.where(), "knee.toml [contact]");
  try {
    contact.number("stiffness", 1.0);
    FAIL() << "a string was read as a number";
  } catch (const ligsim::InputError& e) {
    EXPECT_STREQ(e.what(), "knee.toml:3: [contact] stiffness: expected a number");
  }
  std::vector<TomlTable> bones = contact.tables("bone");
  ASSERT_EQ(bones.size(), 1u);
  EXPECT_EQ(bones[0].where(), "knee.toml [[contact.bone]] #1");
  EXPECT_EQ(bones[0].label("name", ""), "femur");
  try {
    bones[0].reject_unknown_keys();
    FAIL() << "a mistyped key was accepted";
  } catch (const ligsim::InputError& e) {
    EXPECT_STREQ(e.what(), "knee.toml:6: unknown key 'folows' in [[contact.bone]] #1");
  }
  try {
    top.required_table("solver");
    FAIL() << "a missing table was accepted";
  } catch (const ligsim::InputError& e) {
    EXPECT_STREQ(e.what(), "knee.toml: solver: missing (a table)");
  }
}

TEST(TomlTable, OnlyRefusesAKeyBeforeAnyValueIsRead)
{
  EXPECT_EQ(error_of("[m]\nfibre = 1\n",
                     [](TomlTable& t) {
                       t.required_table("m").only({"fiber", "thickness"});
                     }),
            "t.toml:2: unknown key 'fibre' in [m]");
  EXPECT_EQ(error_of("p = [[0, 1], [2]]\n",
                     [](TomlTable& t) {
                       const std::vector<std::vector<double>> p = t.number_lists("p");
                       EXPECT_EQ(p.size(), 2u);
                       EXPECT_EQ(p[1], std::vector<double>{2.0});
                     }),
            "no error");
  EXPECT_EQ(error_of("l = 3\nm = 2.5\n",
                     [](TomlTable& t) {
                       EXPECT_EQ(t.label("l", ""), "3");
                       t.label("m", "");
                     }),
            "t.toml:2: m: expected a label number or name");
}
