/// Parts joined by '+': a bone's meshes in a glTF file, a bone's labels with its cartilage.

#include "common/joined_names.hpp"

#include <gtest/gtest.h>

using namespace ligsim;

TEST(JoinedNames, SplitsOnPlusInOrderAndRefusesAnEmptyName)
{
  EXPECT_EQ(joined_names("femur", "x"), std::vector<std::string>{"femur"});
  EXPECT_EQ(joined_names("2+4+5", "x"), (std::vector<std::string>{"2", "4", "5"}));
  for (const char* bad : {"femur+", "+femur", "a++b", ""}) {
    try {
      joined_names(bad, "label 'q'");
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), "label 'q': an empty name between '+' signs") << bad;
    }
  }
}
