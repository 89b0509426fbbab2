/// The flexion config file: every key read, flags of a missing file kept, errors located.

#include "common/error.hpp"
#include "sim/flexion/flexion_config.hpp"

#include <gtest/gtest.h>

using namespace ligsim::sim;

TEST(FlexionConfig, ReadsEveryTable)
{
  FlexionSettings settings;
  parse_flexion_config(R"(
model = "out/mcl"
angles_deg = [0, 30, 60.5]
mode = "interactive"
images = false
image_angles_deg = [30]
[axis]
method = "points"
first_mm = [0, 0, 0]
second_mm = [1, 0, 0]
[material]
mu_mpa = 1.5
c5_mpa = 100
in_situ_strain = 0.01
[static]
residual_tolerance = 1e-6
[interactive]
angular_speed_deg_s = 90
time_step_s = 0.02
)",
                       "/data", "flexion.toml", settings);
  EXPECT_EQ(settings.model_dir, "/data/out/mcl");
  EXPECT_EQ(settings.angles_deg, (std::vector<double>{0, 30, 60.5}));
  EXPECT_EQ(settings.mode, FlexionMode::interactive);
  EXPECT_FALSE(settings.images);
  EXPECT_EQ(settings.axis.source, AxisSettings::Source::points);
  EXPECT_EQ(settings.axis.second_mm, Eigen::Vector3d::UnitX());
  EXPECT_EQ(settings.material.mu_mpa, 1.5);
  EXPECT_EQ(settings.material.fiber->c5_mpa, 100.0);
  EXPECT_EQ(settings.material.fiber->c4, 61.44); // untouched: the paper's value
  EXPECT_EQ(settings.in_situ_strain, 0.01);
  EXPECT_EQ(settings.newton.residual_tolerance, 1e-6);
  EXPECT_EQ(settings.interactive.angular_speed_deg_s, 90.0);
  EXPECT_NO_THROW(validate(settings));
}

TEST(FlexionConfig, ErrorsNameTheKey)
{
  FlexionSettings settings;
  try {
    parse_flexion_config("[axis]\nposterior = [0, 1, 0]\nposterio = 1\n", "/", "f.toml", settings);
    FAIL() << "an unknown key was accepted";
  } catch (const ligsim::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("posterio"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_flexion_config("mode = \"fast\"\n", "/", "f.toml", settings),
               ligsim::InputError);
  EXPECT_THROW(parse_flexion_config("angles_deg = [0, \"x\"]\n", "/", "f.toml", settings),
               ligsim::InputError);
}

TEST(FlexionConfig, ABadArticularValueNamesItsOwnKey)
{
  for (const auto& [text, key] : {std::pair{"[articular]\nmodulus_mpa = 0\n", "modulus_mpa"},
                                  std::pair{"[articular]\npoisson = 0.6\n", "poisson"},
                                  std::pair{"[articular]\nthickness_mm = -1\n", "thickness_mm"},
                                  std::pair{"[articular]\ngap_mm = -0.5\n", "gap_mm"}}) {
    FlexionSettings settings;
    try {
      parse_flexion_config(text, "/", "f.toml", settings);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const ligsim::InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(key), std::string::npos) << what;
      for (const char* other : {"modulus_mpa", "poisson", "thickness_mm", "gap_mm"}) {
        if (std::string(other) != key) {
          EXPECT_EQ(what.find(other), std::string::npos) << what;
        }
      }
    }
  }
}

TEST(FlexionConfig, ReadsContact)
{
  FlexionSettings settings;
  EXPECT_FALSE(settings.contact.enabled.has_value()); // unset: on, the model has both bones
  EXPECT_TRUE(settings.contact.reshape_overlap);      // unset: "reshape"
  parse_flexion_config(R"(
[contact]
initial_overlap = "deform"
enabled = false
d_hat_mm = 0.5
stiffness_mpa_per_mm = 20
voxel_mm = 0.25
bones = ["tibia"]
)",
                       "/", "flexion.toml", settings);
  EXPECT_EQ(settings.contact.enabled, false);
  EXPECT_EQ(settings.contact.barrier.d_hat_mm, 0.5);
  EXPECT_EQ(settings.contact.barrier.stiffness_mpa_per_mm, 20.0);
  EXPECT_EQ(settings.contact.grid.voxel_mm, 0.25);
  EXPECT_EQ(settings.contact.grid.band_mm, 1.0); // the larger of 1 mm and d_hat + 2 voxels
  EXPECT_EQ(settings.contact.bones, std::vector<std::string>{"tibia"});
  EXPECT_FALSE(settings.contact.reshape_overlap);
  EXPECT_NO_THROW(validate(settings));

  for (const char* bad : {"[contact]\nbones = [\"patella\"]\n", "[contact]\nd_hat_mm = -1\n",
                          "[contact]\nband_mm = 0.1\n", "[contact]\nd_hat = 0.3\n",
                          "[contact]\ninitial_overlap = \"move\"\n"}) {
    FlexionSettings other;
    EXPECT_THROW(
        {
          parse_flexion_config(bad, "/", "flexion.toml", other);
          validate(other);
        },
        ligsim::InputError)
        << bad;
  }
}
