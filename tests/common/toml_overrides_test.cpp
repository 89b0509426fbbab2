#include "common/error.hpp"
#include "common/toml_overrides.hpp"
#include "common/toml_table.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

using namespace ligsim;
using ::testing::HasSubstr;

namespace {

const char* const kConfig = "[tetmesh]\ncell_size_mm = 2.4\nfacet_size_mm = 2.4\n"
                            "[[ligament]]\nname = \"mcl\"\n[[ligament]]\nname = \"acl\"\n"
                            "[ligament.tetmesh]\norder = 1\n";

std::string error_of(const std::vector<std::string>& assignments)
{
  toml::table root = parse_toml(kConfig, "knee.toml");
  try {
    apply_overrides(root, assignments);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

} // namespace

TEST(TomlOverrides, SetsOneKeyAndLeavesItsNeighbours)
{
  toml::table root = parse_toml(kConfig, "knee.toml");
  apply_overrides(root, {"tetmesh.cell_size_mm=1.2", "voxelize.spacing_mm=0.25"});
  TomlTable tetmesh(*root.get_as<toml::table>("tetmesh"), "knee.toml", "[tetmesh]");
  EXPECT_EQ(tetmesh.number("cell_size_mm", 0.0), 1.2);
  EXPECT_EQ(tetmesh.number("facet_size_mm", 0.0), 2.4);
  EXPECT_EQ(root.at_path("voxelize.spacing_mm").value<double>(), 0.25);
}

TEST(TomlOverrides, ReadsTomlValuesAndTakesABareWordAsText)
{
  toml::table root;
  apply_overrides(root, {"a.flag=true", "a.axis=[0, 0, 1]", "a.span=attachments",
                         "a.quoted=\"two words\"", "a.order=2"});
  EXPECT_EQ(root.at_path("a.flag").value<bool>(), true);
  EXPECT_EQ(root.at_path("a.axis").as_array()->size(), 3u);
  EXPECT_EQ(root.at_path("a.span").value<std::string>(), "attachments");
  EXPECT_EQ(root.at_path("a.quoted").value<std::string>(), "two words");
  EXPECT_EQ(root.at_path("a.order").value<int64_t>(), 2);
}

TEST(TomlOverrides, SetsEveryTableOfAnArrayOfTables)
{
  toml::table root = parse_toml(kConfig, "knee.toml");
  apply_overrides(root, {"ligament.tetmesh.order=2"});
  const toml::array& ligaments = *root.get_as<toml::array>("ligament");
  ASSERT_EQ(ligaments.size(), 2u);
  for (const toml::node& ligament : ligaments)
    EXPECT_EQ(ligament.as_table()->at_path("tetmesh.order").value<int64_t>(), 2);
  EXPECT_EQ(ligaments[0].as_table()->at_path("name").value<std::string>(), "mcl");
}

TEST(TomlOverrides, ReadersNameTheAssignmentInTheirMessages)
{
  toml::table root = parse_toml(kConfig, "knee.toml");
  apply_overrides(root, {"tetmesh.cel_size_mm=1.2", "tetmesh.facet_size_mm=fine"});
  TomlTable tetmesh(*root.get_as<toml::table>("tetmesh"), "knee.toml", "[tetmesh]");
  try {
    tetmesh.number("facet_size_mm", 0.0);
    ADD_FAILURE() << "a word read as a number";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("--set tetmesh.facet_size_mm=fine"));
  }
  tetmesh.number("cell_size_mm", 0.0);
  try {
    tetmesh.reject_unknown_keys();
    ADD_FAILURE() << "a misspelt key accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("--set tetmesh.cel_size_mm=1.2"));
    EXPECT_THAT(e.what(), HasSubstr("unknown key 'cel_size_mm'"));
  }
  // Keys the file gave keep the file's line.
  try {
    tetmesh.fail_at("cell_size_mm", "too small");
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("knee.toml:2:"));
  }
}

TEST(TomlOverrides, RefusesWhatIsNotAnAssignment)
{
  EXPECT_THAT(error_of({"tetmesh.cell_size_mm"}), HasSubstr("expected TABLE.KEY=VALUE"));
  EXPECT_THAT(error_of({"=1"}), HasSubstr("expected TABLE.KEY=VALUE"));
  EXPECT_THAT(error_of({"tetmesh..order=2"}), HasSubstr("expected TABLE.KEY=VALUE"));
  EXPECT_THAT(error_of({"[tetmesh]order=2"}), HasSubstr("expected TABLE.KEY=VALUE"));
  EXPECT_THAT(error_of({"tetmesh.order="}), HasSubstr("the value is not TOML"));
  EXPECT_THAT(error_of({"tetmesh.order=\"2"}), HasSubstr("--set tetmesh.order=\"2"));
  // Not TOML, and no TOML string either (a control character): refused, not read.
  EXPECT_THAT(error_of({"tetmesh.span=a\x01b"}), HasSubstr("the value is not TOML"));
  EXPECT_THAT(error_of({"tetmesh.span=two\nlines"}), HasSubstr("the value is not TOML"));
}

TEST(TomlOverrides, AFlagsAssignmentReadsBackAsTheSameValue)
{
  // What a convenience flag sets must reach the reader unchanged: doubles to the last bit, a
  // whole number still a float, text with quotes and backslashes, lists.
  const double third = 1.0 / 3.0;
  toml::table root;
  apply_overrides(root, {toml_assignment("a.third", third), toml_assignment("a.whole", 2.0),
                         toml_assignment("a.tiny", 1e-300), toml_assignment("a.order", 2),
                         toml_assignment("a.on", false),
                         toml_assignment("a.text", std::string("say \"hi\" \\ there")),
                         toml_assignment("a.axis", std::vector<double>{0.1, -2.0, 3e7}),
                         toml_assignment("a.ids", std::vector<int>{4, 5}),
                         toml_assignment("a.names", std::vector<std::string>{"ACL", "MCL"})});
  EXPECT_EQ(root.at_path("a.third").value<double>(), third);
  ASSERT_TRUE(root.at_path("a.whole").is_floating_point());
  EXPECT_EQ(root.at_path("a.whole").value<double>(), 2.0);
  EXPECT_EQ(root.at_path("a.tiny").value<double>(), 1e-300);
  EXPECT_EQ(root.at_path("a.order").value<int64_t>(), 2);
  EXPECT_EQ(root.at_path("a.on").value<bool>(), false);
  EXPECT_EQ(root.at_path("a.text").value<std::string>(), "say \"hi\" \\ there");
  const toml::array& axis = *root.at_path("a.axis").as_array();
  ASSERT_EQ(axis.size(), 3u);
  EXPECT_EQ(axis[0].value<double>(), 0.1);
  EXPECT_EQ(axis[1].value<double>(), -2.0);
  EXPECT_EQ(axis[2].value<double>(), 3e7);
  EXPECT_EQ(root.at_path("a.ids").as_array()->size(), 2u);
  EXPECT_EQ((*root.at_path("a.names").as_array())[1].value<std::string>(), "MCL");
}
