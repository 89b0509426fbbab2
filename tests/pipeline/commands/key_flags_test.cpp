/// Flags that are short names for config keys: what a parsed command line assigns, under a
/// prefix, and the help that names the keys.

#include "pipeline/commands/key_flags.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace {

using ligsim::cli::KeyFlags;
using Texts = std::vector<std::string>;

struct Command {
  CLI::App app;
  KeyFlags flags;
  Command()
  {
    flags.add<double>(app, "--cell-size", "max circumradius, mm", {"tetmesh.cell_size_mm"});
    flags.add<double>(app, "--distance", "distance, mm (default 1)",
                      {"attachments.femur.distance_mm", "attachments.tibia.distance_mm"});
    flags.add<Texts>(app, "--names", "names", {"ligaments"})->delimiter(',');
    flags.add<std::string>(app, "--contact", "on or off", {"contact.enabled"},
                           [](const std::string& on, const Texts& keys) {
                             return Texts{ligsim::toml_assignment(keys[0], on == "on")};
                           });
    flags.add_switch(app, "--strict", "refuse defects", "input.strict");
  }
  void parse(Texts arguments)
  {
    arguments.insert(arguments.begin(), "ligsim");
    std::vector<const char*> argv;
    for (const std::string& a : arguments)
      argv.push_back(a.c_str());
    app.parse(static_cast<int>(argv.size()), argv.data());
  }
};

TEST(KeyFlags, TheFlagsGivenBecomeTheirKeysInDeclarationOrder)
{
  Command c;
  c.parse({"--contact", "off", "--distance", "2.5", "--strict"});
  EXPECT_EQ(c.flags.assignments(),
            (Texts{"attachments.femur.distance_mm=2.5", "attachments.tibia.distance_mm=2.5",
                   "contact.enabled=false", "input.strict=true"}));
  EXPECT_EQ(c.flags.assignments("ligament."),
            (Texts{"ligament.attachments.femur.distance_mm=2.5",
                   "ligament.attachments.tibia.distance_mm=2.5", "ligament.contact.enabled=false",
                   "ligament.input.strict=true"}));
  EXPECT_EQ(c.flags.given_under("attachments."), (Texts{"--distance"}));
  EXPECT_TRUE(c.flags.given_under("tetmesh.").empty());
}

TEST(KeyFlags, NoFlagGivenAssignsNothing)
{
  Command c;
  c.parse({});
  EXPECT_TRUE(c.flags.assignments().empty());
}

TEST(KeyFlags, ASwitchGivenAsFalseSetsNothing)
{
  Command c;
  c.parse({"--strict=false"});
  EXPECT_TRUE(c.flags.assignments().empty());
}

TEST(KeyFlags, ListsAndWholeNumbersAreWrittenAsTheirTomlTypes)
{
  Command c;
  c.parse({"--names", "MCL,LCL", "--cell-size", "1"});
  EXPECT_EQ(c.flags.assignments(),
            (Texts{"tetmesh.cell_size_mm=1.0", "ligaments=[\"MCL\", \"LCL\"]"}));
}

TEST(KeyFlags, TheHelpNamesTheKeys)
{
  Command c;
  EXPECT_EQ(c.app.get_option("--cell-size")->get_description(),
            "max circumradius, mm (--set tetmesh.cell_size_mm)");
  EXPECT_EQ(c.app.get_option("--distance")->get_description(),
            "distance, mm (default 1; --set attachments.femur.distance_mm and "
            "attachments.tibia.distance_mm)");
}

} // namespace
