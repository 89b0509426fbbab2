#include "sim/kinematics/kinematics_csv.hpp"
#include "sim/kinematics/knee_path.hpp"

#include "common/error.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace ligsim::sim {
namespace {

namespace fs = std::filesystem;

TEST(PassiveCoupling, MatchesTheTabulatedWalkerKnee)
{
  // OpenSim's Rajagopal knee tabulates Walker et al.'s coupling every 10 degrees: internal
  // rotation 8.63, 13.18, 14.88, 14.99 deg and adduction 1.70, 1.77, 0.65, -0.10 deg at 30,
  // 60, 90 and 120 degrees of flexion.
  const double flexion[] = {30.0, 60.0, 90.0, 120.0};
  const double internal[] = {8.63, 13.18, 14.88, 14.99};
  const double varus[] = {1.70, 1.77, 0.65, -0.10};
  for (int k = 0; k < 4; ++k) {
    const JointPose pose = passive_coupling(flexion[k], false);
    EXPECT_NEAR(pose.internal_rotation_deg, internal[k], 0.01) << flexion[k];
    EXPECT_NEAR(pose.varus_deg, varus[k], 0.01) << flexion[k];
    EXPECT_EQ(pose.anterior_mm, 0.0);
  }
  const JointPose rest = passive_coupling(0.0, true);
  EXPECT_EQ(rest.internal_rotation_deg, 0.0);
  EXPECT_EQ(rest.anterior_mm, 0.0);
  // Past its range the coupling holds its last value.
  EXPECT_DOUBLE_EQ(passive_coupling(140.0, true).internal_rotation_deg,
                   passive_coupling(120.0, true).internal_rotation_deg);
  EXPECT_GT(passive_coupling(90.0, true).anterior_mm, 5.0);
}

TEST(KneePath, TableInterpolatesLinearlyAndHoldsItsEnds)
{
  const KneePath path = KneePath::table(
      KneePath::Parameter::flexion_deg, {0.0, 10.0, 30.0},
      {JointPose{0, 0, 0, 0, 0, 0}, JointPose{10, 1, 4, 0, 1, 0}, JointPose{30, 2, 8, 0, 3, 0}},
      "test");
  EXPECT_NEAR(path.at(20.0).internal_rotation_deg, 6.0, 1e-12);
  EXPECT_NEAR(path.at(20.0).anterior_mm, 2.0, 1e-12);
  EXPECT_NEAR(path.at(40.0).flexion_deg, 30.0, 1e-12);
  EXPECT_THROW(
      KneePath::table(KneePath::Parameter::time_s, {0.0, 0.0}, {JointPose{}, JointPose{}}, "test"),
      InputError);
}

TEST(FemurPath, RunsTheParameterOverTheLoadFactor)
{
  JointCoordinateSystem jcs;
  jcs.side = -1;
  const FemurPath path(jcs, KneePath::passive(false), 0.0, 90.0);
  EXPECT_NEAR(path.joint_pose_at(0.5).flexion_deg, 45.0, 1e-12);
  EXPECT_TRUE(path.pose(0.0).isApprox(Eigen::Isometry3d::Identity(), 1e-14));
  const JointPose back = joint_pose(jcs, path.pose(1.0));
  EXPECT_NEAR(back.internal_rotation_deg, passive_coupling(90.0, false).internal_rotation_deg,
              1e-9);
}

class KinematicsCsv : public ::testing::Test {
protected:
  fs::path write(const std::string& text)
  {
    const fs::path file =
        fs::temp_directory_path() /
        ("ligsim_kinematics_" +
         std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + ".csv");
    std::ofstream(file) << text;
    return file;
  }
};

TEST_F(KinematicsCsv, ReadsRowsPerAngleWithAbsentColumnsAtZero)
{
  const KneePath path = read_kinematics_csv(
      write("# robot export\nflexion_deg, internal_rotation_deg ,anterior_mm\n0,0,0\n"
            "30,5.5,1.25\n\n60,9,2\n"));
  EXPECT_EQ(path.parameter(), KneePath::Parameter::flexion_deg);
  ASSERT_EQ(path.knots().size(), 3u);
  EXPECT_NEAR(path.at(45.0).internal_rotation_deg, 7.25, 1e-12);
  EXPECT_EQ(path.at(45.0).varus_deg, 0.0);
}

TEST_F(KinematicsCsv, ReadsAMotionInTime)
{
  const KneePath path = read_kinematics_csv(
      write("time_s,flexion_deg,varus_deg,internal_rotation_deg,lateral_mm,anterior_mm,"
            "proximal_mm\n0,0,0,0,0,0,0\n0.5,40,1,6,0.1,2,0.5\n1.0,20,0.5,3,0,1,0.2\n"));
  EXPECT_EQ(path.parameter(), KneePath::Parameter::time_s);
  EXPECT_NEAR(path.at(0.75).flexion_deg, 30.0, 1e-12); // flexion may go up and down in time
}

TEST_F(KinematicsCsv, BadFilesAreClearErrors)
{
  const auto message = [&](const std::string& text) {
    try {
      read_kinematics_csv(write(text));
    } catch (const InputError& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("flexion_deg,twist_deg\n0,0\n").find("unknown column 'twist_deg'"),
            std::string::npos);
  EXPECT_NE(message("varus_deg\n0\n").find("no flexion_deg column"), std::string::npos);
  EXPECT_NE(message("flexion_deg,varus_deg\n0,0\n10\n").find(":3: 1 fields"), std::string::npos);
  EXPECT_NE(message("flexion_deg\n0\nten\n").find("'ten' is not a finite number"),
            std::string::npos);
  EXPECT_NE(message("flexion_deg\n0\n30\n20\n").find("must increase"), std::string::npos);
  EXPECT_NE(message("# nothing\n").find("no header line"), std::string::npos);
  EXPECT_NE(message("flexion_deg\n").find("no rows"), std::string::npos);
  EXPECT_THROW(read_kinematics_csv("/nonexistent/kinematics.csv"), InputError);
}

} // namespace
} // namespace ligsim::sim
