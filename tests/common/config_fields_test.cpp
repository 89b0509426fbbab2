/// The parameter lists' readers and writers (common/config_section.hpp, common/fields_json.hpp)
/// on one list holding every kind of field: a config read, written as JSON and read back gives
/// the same parameters; a required key, an angle in degrees and an enumerated value behave as
/// their kinds say.

#include "common/config_section.hpp"
#include "common/error.hpp"
#include "common/fields_json.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace ligsim;

namespace {

enum class Law { soft, hard };

std::string to_string(Law law)
{
  return law == Law::soft ? "soft" : "hard";
}

struct Parameters {
  double modulus_mpa = 0.0;
  int steps = 3;
  bool verbose = false;
  double turn_rad = 0.5;
  Law law = Law::soft;
};

template <class P, class Visit> void visit_parameters(P& p, Visit&& visit)
{
  visit("modulus_mpa", required(p.modulus_mpa));
  visit("steps", p.steps);
  visit("verbose", p.verbose);
  visit("turn_deg", degrees(p.turn_rad));
  visit("law", choice(p.law, to_string, {Law::soft, Law::hard}));
}

Parameters read_config(const std::string& text)
{
  const toml::table root = parse_toml(text, "c.toml");
  Parameters p;
  read_fields(&root, "table", "table", "c.toml", p,
              [](auto& q, auto&& v) { visit_parameters(q, v); });
  return p;
}

std::string error_of(const std::string& text)
{
  try {
    read_config(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

} // namespace

TEST(ConfigFields, AConfigWrittenAsJsonReadsBackTheSame)
{
  const Parameters p =
      read_config("[table]\nmodulus_mpa = 2.5\nsteps = 7\nturn_deg = 90\nlaw = \"hard\"\n");
  EXPECT_EQ(p.modulus_mpa, 2.5);
  EXPECT_EQ(p.steps, 7);
  EXPECT_FALSE(p.verbose); // not given: the declaration's default
  EXPECT_DOUBLE_EQ(p.turn_rad, M_PI / 2.0);
  EXPECT_EQ(p.law, Law::hard);

  nlohmann::json json;
  visit_parameters(p, FieldJsonWriter{json});
  EXPECT_DOUBLE_EQ(json["turn_deg"].get<double>(), 90.0);
  EXPECT_EQ(json["law"], "hard");
  Parameters back;
  const std::string where = "knee.json";
  visit_parameters(back, FieldJsonReader{json, where});
  EXPECT_EQ(back.modulus_mpa, p.modulus_mpa);
  EXPECT_EQ(back.steps, p.steps);
  EXPECT_EQ(back.verbose, p.verbose);
  EXPECT_DOUBLE_EQ(back.turn_rad, p.turn_rad);
  EXPECT_EQ(back.law, p.law);

  json["law"] = "medium";
  try {
    visit_parameters(back, FieldJsonReader{json, where});
    ADD_FAILURE() << "an unknown choice was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("knee.json: 'law': expected \"soft\" or \"hard\""),
              std::string::npos)
        << e.what();
  }
  json.erase("steps");
  EXPECT_THROW(visit_parameters(back, FieldJsonReader{json, where}), InputError);
}

TEST(ConfigFields, ARequiredKeyIsMissingAndABadChoiceNamesTheChoices)
{
  EXPECT_NE(error_of("[table]\nsteps = 2\n").find("modulus_mpa: missing"), std::string::npos)
      << error_of("[table]\nsteps = 2\n");
  const std::string bad = error_of("[table]\nmodulus_mpa = 1.0\nlaw = \"medium\"\n");
  EXPECT_NE(bad.find("expected \"soft\" or \"hard\", got \"medium\""), std::string::npos) << bad;
  EXPECT_NE(error_of("[table]\nmodulus_mpa = 1.0\nturn = 3\n").find("unknown key 'turn'"),
            std::string::npos);
  // An absent angle keeps its radians exactly (no round trip through degrees).
  EXPECT_EQ(read_config("[table]\nmodulus_mpa = 1.0\n").turn_rad, 0.5);
}
