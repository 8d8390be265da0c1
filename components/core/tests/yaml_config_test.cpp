#include "uavmot/core/yaml_config.hpp"

#include <gtest/gtest.h>

namespace uavmot {
namespace {

TEST(YamlConfig, ReadsValuesAndKeepsDefaults) {
  const auto root = ConfigNode::load_string("a: 3\nb: 0.5\nname: x\nflag: true\n", "t.yaml");
  int a = 1, missing = 7;
  double b = 0;
  std::string name;
  bool flag = false;
  root.read("a", a, 0, 10);
  root.read("missing", missing, 0, 10);
  root.read("b", b, 0.0, 1.0);
  root.read("name", name);
  root.read("flag", flag);
  EXPECT_EQ(a, 3);
  EXPECT_EQ(missing, 7);
  EXPECT_DOUBLE_EQ(b, 0.5);
  EXPECT_EQ(name, "x");
  EXPECT_TRUE(flag);
}

TEST(YamlConfig, ErrorsNameFileLineAndKey) {
  const auto root = ConfigNode::load_string("motion:\n  max_features: lots\n", "cfg.yaml");
  int value = 0;
  try {
    root.child("motion").read("max_features", value, 1, 100);
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "cfg.yaml:2: motion.max_features: expected an integer, got 'lots'");
  }
}

TEST(YamlConfig, RejectsOutOfRangeAndUnknownKeysWithSuggestion) {
  const auto root = ConfigNode::load_string("max_featurs: 5\n", "cfg.yaml");
  try {
    root.expect_only({"max_features", "quality"});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean 'max_features'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("cfg.yaml:1"), std::string::npos) << e.what();
  }
  int v = 0;
  const auto big = ConfigNode::load_string("n: 500\n", "c.yaml");
  EXPECT_THROW(big.read("n", v, 0, 10), InputError);
}

TEST(YamlConfig, SyntaxErrorsAndMissingFilesAreInputErrors) {
  EXPECT_THROW(ConfigNode::load_string("a: [1, 2\n", "bad.yaml"), InputError);
  EXPECT_THROW(ConfigNode::load_file("/nonexistent/uavmot.yaml"), InputError);
  EXPECT_THROW(ConfigNode::load_string("- 1\n- 2\n", "list.yaml"), InputError);
}

TEST(YamlConfig, ComplexKeysAreInputErrors) {
  // Found by config_fuzz (tests/fuzz/regressions/config/complex_key): "? key" makes a key that is
  // itself a node; keys() converted it to a string and yaml-cpp threw TypedBadConversion.
  const auto root = ConfigNode::load_string("motion:\n  max_features: 10\n? [a, b]\n: 3\n", "c.yaml");
  try {
    root.expect_only({"motion"});
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "c.yaml:3: keys must be plain names");
  }
  const auto nested = ConfigNode::load_string("motion:\n  ? {x: 1}\n  : 2\n", "c.yaml");
  EXPECT_THROW(nested.child("motion").keys(), InputError);
  EXPECT_EQ(ConfigNode::load_string("? plain\n: 1\n", "c.yaml").keys(), std::vector<std::string>{"plain"});
}

TEST(YamlConfig, ChoicesAreValidated) {
  const auto root = ConfigNode::load_string("mode: sideways\n", "c.yaml");
  std::string mode = "live";
  EXPECT_THROW(root.read_choice("mode", mode, {"live", "lossless"}), InputError);
  EXPECT_EQ(mode, "live");
}

}  // namespace
}  // namespace uavmot
