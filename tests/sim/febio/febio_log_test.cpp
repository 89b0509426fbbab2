/// Reading FEBio's .log: data records by number and time, how the run ended, FEBio's error box,
/// and a malformed record named with its line.

#include "common/error.hpp"
#include "sim/febio/febio_log.hpp"

#include <gtest/gtest.h>

using namespace ligsim;
using namespace ligsim::sim;

namespace {

// As FEBio 4.11 writes it (shortened).
const char* const log_text =
    R"( *************************************************************************
 *                               WARNING                                 *
 * No force acting on the system.                                        *
 *************************************************************************

------- converged at time : 1


Data Record #1
===========================================================================
Step = 1
Time = 1
Data = x;y;z
1 0 0 0
2 1 0.5 -2.25e-05

Data Record #2
===========================================================================
Step = 1
Time = 1
Data = x;y;z;qx;qy;qz;qw;Fx;Fy;Fz;Mx;My;Mz
2 1 1 22 0 0 0 1 0.0631966013562 0.0631966013562 36.7387661915 0.758 -0.758 -4.4e-16

Data Record #1
===========================================================================
Step = 3
Time = 2
Data = x;y;z
1 0 0 0.1
2 1 0.5 3

 N O R M A L   T E R M I N A T I O N
)";

} // namespace

TEST(FebioLog, ReadsRecordsByNumberAndTime)
{
  const FebioLog log = parse_febio_log(log_text, "test.log");
  EXPECT_TRUE(log.normal_termination);
  EXPECT_FALSE(log.error_termination);
  EXPECT_TRUE(log.error.empty()); // a warning is not an error
  ASSERT_EQ(log.records.size(), 3u);
  const FebioRecord* nodes = log.find(1, 2.0);
  ASSERT_NE(nodes, nullptr);
  EXPECT_EQ(nodes->step, 3);
  EXPECT_EQ(nodes->variables, (std::vector<std::string>{"x", "y", "z"}));
  EXPECT_EQ(nodes->rows.at(2), (std::vector<double>{1.0, 0.5, 3.0}));
  EXPECT_EQ(log.find(1, 1.0)->rows.at(2)[2], -2.25e-05);
  const FebioRecord* rigid = log.find(2, 1.0);
  ASSERT_NE(rigid, nullptr);
  EXPECT_EQ(rigid->rows.at(2).size(), 13u);
  EXPECT_EQ(rigid->rows.at(2)[9], 36.7387661915);
  EXPECT_EQ(log.find(2, 2.0), nullptr);
  EXPECT_EQ(log.find(3, 1.0), nullptr);
}

TEST(FebioLog, ReportsFebiosLastError)
{
  const FebioLog log = parse_febio_log(R"(
 *************************************************************************
 *                                ERROR                                  *
 * Negative jacobian detected.                                           *
 *************************************************************************
Retrying time step. Retry attempt 1 of max 10
Reading file knee.feb ...FAILED!

 *************************************************************************
 *                                ERROR                                  *
 * tag "ElementData" (line 302) : invalid value for attribute "type"     *
 *************************************************************************

 E R R O R   T E R M I N A T I O N
)",
                                       "console");
  EXPECT_FALSE(log.normal_termination);
  EXPECT_TRUE(log.error_termination);
  EXPECT_EQ(log.error, "tag \"ElementData\" (line 302) : invalid value for attribute \"type\"");
}

TEST(FebioLog, NamesTheLineOfAMalformedRecord)
{
  try {
    parse_febio_log("Data Record #1\n=====\nStep = 1\nTime = 1\nData = x;y;z\n1 0 0\n", "a.log");
    FAIL() << "accepted a row with two values for three variables";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("a.log, line 6"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_febio_log("Data Record #1\nStep = 1\n", "b.log"), InputError);
}
