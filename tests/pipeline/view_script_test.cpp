#include "common/error.hpp"
#include "pipeline/view/view_script.hpp"
#include "tests/pipeline/cli_runner.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

using namespace ligsim;
using namespace ligsim::test;

namespace {

std::filesystem::path script_file(const std::string& name, const std::string& text)
{
  const std::filesystem::path file = fresh_folder(name) += ".csv";
  std::ofstream(file) << text;
  return file;
}

/// The InputError's message when reading `text`, or "" when it reads.
std::string rejection(const std::string& text)
{
  try {
    cli::ViewScript::read(script_file("view_script_bad", text));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

} // namespace

TEST(ViewScript, TheSliderIsLinearBetweenRowsAndHeldOutside)
{
  const cli::ViewScript script = cli::ViewScript::read(
      script_file("view_script_good", "angle_deg,time_s\n10,0.5\n90,2.5\n90,3\n"));
  EXPECT_DOUBLE_EQ(script.at(0.0), 10.0);
  EXPECT_DOUBLE_EQ(script.at(1.5), 50.0);
  EXPECT_DOUBLE_EQ(script.at(2.75), 90.0);
  EXPECT_DOUBLE_EQ(script.at(9.0), 90.0);
  EXPECT_DOUBLE_EQ(script.end_s(), 3.0);
}

TEST(ViewScript, ABadScriptIsAnErrorNamingItsLine)
{
  EXPECT_NE(rejection("time,angle_deg\n0,0\n").find("no column time_s"), std::string::npos);
  EXPECT_NE(rejection("time_s,angle_deg\n0,0\n1,x\n").find("line 3"), std::string::npos);
  EXPECT_NE(rejection("time_s,angle_deg\n0,0\n1,10\n1,20\n").find("strictly increasing"),
            std::string::npos);
  EXPECT_NE(rejection("time_s,angle_deg\n").find("no rows"), std::string::npos);
  EXPECT_NE(rejection("").find("is empty"), std::string::npos);
}

TEST(ViewScript, AHandsPathGivesEachOfItsColumns)
{
  const cli::ViewScript script = cli::ViewScript::read(
      script_file("view_script_hand", "time_s,y_mm,x_mm\n0.1,0,5\n0.3,2,9\n"), {"x_mm", "y_mm"});
  EXPECT_DOUBLE_EQ(script.start_s(), 0.1);
  EXPECT_DOUBLE_EQ(script.at(0.2, 0), 7.0);
  EXPECT_DOUBLE_EQ(script.at(0.2, 1), 1.0);
  EXPECT_DOUBLE_EQ(script.at(1.0, 0), 9.0);
  try {
    cli::ViewScript::read(script_file("view_script_hand_bad", "time_s,x_mm\n0,5\n"),
                          {"x_mm", "y_mm"});
    ADD_FAILURE() << "a script without y_mm was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no column y_mm (it needs time_s, x_mm, y_mm)"),
              std::string::npos)
        << e.what();
  }
}
