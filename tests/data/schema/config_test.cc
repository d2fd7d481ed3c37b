#include "data/schema/config.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace kelvin::data {
namespace {

using ::testing::HasSubstr;

const char* kShip = R"(ship:
  name: test
  Lpp: 7.0
hull:
  Y_v: -0.315
  Yr: 0.083
)";

TEST(ConfigTest, ReadsValuesAndDefaults) {
  const auto root = ConfigNode::LoadString(kShip, "ship.yaml");
  EXPECT_DOUBLE_EQ(root["ship"].Get<double>("Lpp"), 7.0);
  EXPECT_EQ(root["ship"].Get<std::string>("name"), "test");
  EXPECT_DOUBLE_EQ(root["hull"].Get<double>("N_v", 1.5), 1.5);
  EXPECT_TRUE(root.Has("hull"));
  EXPECT_FALSE(root.Has("rudder"));
}

TEST(ConfigTest, UnknownKeyNamesFileLineKeyAndValidKeys) {
  const auto root = ConfigNode::LoadString(kShip, "ship.yaml");
  try {
    root["hull"].ExpectKeys({"Y_v", "Y_r", "N_v"});
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    const std::string msg = e.what();
    EXPECT_THAT(msg, HasSubstr("ship.yaml:6"));
    EXPECT_THAT(msg, HasSubstr("unknown key 'hull.Yr'"));
    EXPECT_THAT(msg, HasSubstr("valid keys: Y_v, Y_r, N_v"));
    EXPECT_THAT(msg, HasSubstr("did you mean 'Y_r'?"));
  }
}

TEST(ConfigTest, MissingKeyIsNamed) {
  const auto root = ConfigNode::LoadString(kShip, "ship.yaml");
  try {
    root["ship"].Get<double>("B");
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("missing required key 'ship.B'"));
    EXPECT_THAT(e.what(), HasSubstr("ship.yaml:2"));
  }
}

TEST(ConfigTest, WrongTypeNamesValueAndExpectation) {
  const auto root = ConfigNode::LoadString("a:\n  b: fast\n", "case.yaml");
  try {
    root["a"].Get<double>("b");
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("case.yaml:2: key 'a.b' = 'fast': expected a number"));
  }
}

TEST(ConfigTest, NonPositiveValueRejected) {
  const auto root = ConfigNode::LoadString("mass: -3\n", "ship.yaml");
  EXPECT_THROW(root.GetPositive("mass"), ConfigError);
  try {
    root.GetPositive("mass");
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("key 'mass' = '-3': expected a positive number"));
  }
}

TEST(ConfigTest, SyntaxErrorNamesLine) {
  try {
    ConfigNode::LoadString("a: [1, 2\nb: 3\n", "bad.yaml");
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("bad.yaml:"));
    EXPECT_THAT(e.what(), HasSubstr("YAML syntax error"));
  }
}

TEST(ConfigTest, MissingFile) {
  EXPECT_THROW(ConfigNode::LoadFile("/nonexistent/ship.yaml"), ConfigError);
}

// Found by the mesh_case_yaml fuzz target: a ship path naming a directory
// ended the program (std::terminate on the stream's read error).
TEST(ConfigTest, DirectoryIsRefusedByName) {
  try {
    ConfigNode::LoadFile("/");
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("/: is a directory; expected a YAML file"));
  }
}

TEST(ConfigTest, ListsOfNumbers) {
  const auto root = ConfigNode::LoadString("v: [1, 2.5, -3]\nw: [1, x]\n", "l.yaml");
  EXPECT_EQ(root.Get<std::vector<double>>("v"), (std::vector<double>{1, 2.5, -3}));
  try {
    root.Get<std::vector<double>>("w");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("key 'w[1]' = 'x': expected a number"));
  }
}

TEST(ClosestMatchTest, SuggestsOnlyCloseWords) {
  const std::vector<std::string> keys{"mesh", "physics", "schemes"};
  EXPECT_EQ(ClosestMatch("phisics", keys).value_or(""), "physics");
  EXPECT_FALSE(ClosestMatch("zzzzzzzzzz", keys).has_value());
}

// ClosestMatch gives up on a candidate once it cannot beat the best so far;
// the answer is the one of the full edit distance: the first of the closest.
TEST(ClosestMatchTest, FirstOfTheClosestAndLongWords) {
  const std::vector<std::string> keys{"Y_vvr", "Y_v", "Y_r", "Y_vr"};
  EXPECT_EQ(ClosestMatch("Y_vr", keys).value_or(""), "Y_vr");
  EXPECT_EQ(ClosestMatch("Y_vx", keys).value_or(""), "Y_v");
  EXPECT_EQ(ClosestMatch("Y_vr", std::vector<std::string>{"Y_vvr", "Y_v"}).value_or(""), "Y_vvr");
  const std::string long_key(300, 'a');
  const std::vector<std::string> long_keys{std::string(290, 'a') + "bbbbbbbbbb", long_key + "x", "a"};
  EXPECT_EQ(ClosestMatch(long_key, long_keys).value_or(""), long_key + "x");
  EXPECT_EQ(ClosestMatch(std::string(300, 'b'), long_keys).value_or("-"), "-");
}

TEST(ConfigTest, ExpectKeysNamesTheFirstUnknownKey) {
  const auto root = ConfigNode::LoadString("ship:\n  name: a\n  lenght: 2\n  bem: 3\n", "ship.yaml");
  EXPECT_NO_THROW(root["ship"].ExpectKeys({"name", "lenght", "bem"}));
  try {
    root["ship"].ExpectKeys({"name", "length", "beam"});
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("ship.yaml:3: unknown key 'ship.lenght'; valid keys: name, length, beam "
                                    "(did you mean 'length'?)"));
  }
}

// Found by the fuzz targets: yaml-cpp's own exception escaped for a key that
// is a list or a map.
TEST(ConfigTest, AListOrAMapAsAKeyIsAConfigError) {
  const auto root = ConfigNode::LoadString("ship:\n  [0, 2.5]: 1\n", "ship.yaml");
  try {
    root["ship"].ExpectKeys({"name"});
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("ship.yaml:2: a list is used as a key in 'ship'; expected a key name"));
  }
  EXPECT_THROW(ConfigNode::LoadString("{a: 1}: 2\n", "case.yaml").Keys(), ConfigError);
}

}  // namespace
}  // namespace kelvin::data
