#include "io/yaml_reader.hpp"

#include <gtest/gtest.h>

namespace biped {
namespace {

TEST(ApplyOverride, SetsNestedAndNewKeysAndListItems) {
  YAML::Node root = YAML::Load("controller: {stabilizer: true}\ncommands:\n  - {t: 0, vx: 0}\n  - {t: 1, vx: 0.5}\n");
  apply_override(root, "controller.stabilizer=false");
  apply_override(root, "simulation.timestep=0.0005");
  apply_override(root, "commands.1.vx=0.7");
  EXPECT_FALSE(root["controller"]["stabilizer"].as<bool>());
  EXPECT_DOUBLE_EQ(root["simulation"]["timestep"].as<double>(), 0.0005);
  EXPECT_DOUBLE_EQ(root["commands"][1]["vx"].as<double>(), 0.7);
}

TEST(ApplyOverride, RejectsMalformedAssignments) {
  YAML::Node root = YAML::Load("duration: 5\ncommands: [{t: 0}]\n");
  EXPECT_THROW(apply_override(root, "duration"), InputError);
  EXPECT_THROW(apply_override(root, "=3"), InputError);
  EXPECT_THROW(apply_override(root, "duration.x=3"), InputError);
  EXPECT_THROW(apply_override(root, "commands.4.vx=3"), InputError);
}

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(YamlReader, ErrorsNameFileKeyAndLine) {
  const YAML::Node root = YAML::Load("a: 1\nb:\n  c: .nan\n  d: -2\n  e: yes please\n");
  const YamlReader r("scenario.yaml");
  EXPECT_EQ(message_of([&] { r.number(root["b"], "b", "c"); }),
            "scenario.yaml:3: key 'b.c': must be a finite number (got '.nan')");
  EXPECT_EQ(message_of([&] { r.positive_or(root["b"], "b", "d", 1.0); }),
            "scenario.yaml:4: key 'b.d': must be positive (got -2)");
  EXPECT_NE(message_of([&] { r.boolean_or(root["b"], "b", "e", true); }).find("key 'b.e'"), std::string::npos);
  EXPECT_NE(message_of([&] { r.expect_keys(root, "", {"a"}); }).find("scenario.yaml:2: key 'b': unknown key"),
            std::string::npos);
  EXPECT_NE(message_of([&] { r.number(root, "", "zzz"); }).find("key 'zzz': missing"), std::string::npos);
}

TEST(YamlReader, OverriddenValuesAreReportedAsSuch) {
  YAML::Node root = YAML::Load("duration: 5\n");
  apply_override(root, "duration=-1");
  const YamlReader r("s.yaml");
  EXPECT_EQ(message_of([&] { r.positive_or(root, "", "duration", 1.0); }),
            "s.yaml (--set): key 'duration': must be positive (got -1)");
}

}  // namespace
}  // namespace biped
